#include <fmt/format.h>

#include "anascan/gui/field_view_state.hpp"

namespace anascan::gui {
namespace {

std::string triangle_count(std::size_t n) {
    if (n >= 10'000'000) return fmt::format("{:.0f} M", double(n) * 1e-6);
    if (n >= 1'000'000) return fmt::format("{:.1f} M", double(n) * 1e-6);
    if (n >= 10'000) return fmt::format("{:.0f} k", double(n) * 1e-3);
    return fmt::format("{}", n);
}

}  // namespace

std::string mesh_summary(const MeshViewState& mesh) {
    switch (mesh.status) {
        case MeshViewState::Status::kNone:
            return {};
        case MeshViewState::Status::kMaking:
            return "Making the mesh" + (mesh.message.empty() ? "" : ": " + mesh.message);
        case MeshViewState::Status::kFailed:
            return "Mesh failed: " + mesh.message;
        case MeshViewState::Status::kReady:
            break;
    }
    std::string text = fmt::format(
        "Mesh: {} triangles, {:.3f} m\u00b2, {:.1f} % interpolated, {}; {} scan{}, {:.1f} mm, "
        "{:.1f} s",
        triangle_count(mesh.triangles), mesh.area_m2, 100.0 * mesh.interpolated_share,
        mesh.closed ? "closed" : "not closed", mesh.scans, mesh.scans == 1 ? "" : "s",
        mesh.resolution_mm, mesh.seconds);
    if (!mesh.outdated.empty()) text += " (outdated: " + mesh.outdated + ")";
    return text;
}

}  // namespace anascan::gui
