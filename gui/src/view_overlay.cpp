#include "anascan/gui/view_overlay.hpp"

#include <fmt/format.h>
#include <imgui.h>

#include <algorithm>
#include <cmath>

#include "anascan/gui/scan_colors.hpp"
#include "anascan/processing/coverage/coverage.hpp"
#include "anascan/processing/surface/fragment_model.hpp"

namespace anascan::gui {
namespace {

std::string length_label(double length_m) {
    if (length_m >= 1.0) return fmt::format("{:g} m", length_m);
    if (length_m >= 0.01) return fmt::format("{:g} cm", length_m * 100.0);
    return fmt::format("{:g} mm", length_m * 1000.0);
}

ImU32 to_imgui(Rgb8 c) { return IM_COL32(c.r, c.g, c.b, 255); }

std::vector<LegendEntry> scan_legend(const FieldViewState& state, std::size_t max_scans) {
    std::vector<std::int64_t> seqs;
    for (const ScanRow& row : state.scans)
        if (row.state == ScanRowState::kRegistered) seqs.push_back(row.seq);
    std::vector<LegendEntry> entries;
    const std::size_t first = seqs.size() > max_scans ? seqs.size() - max_scans : 0;
    if (first > 0) entries.push_back({.color = {150, 150, 150}, .label = "... older scans"});
    for (std::size_t i = first; i < seqs.size(); ++i)
        entries.push_back(
            {.color = scan_palette_color(seqs[i]), .label = fmt::format("scan {}", seqs[i])});
    return entries;
}

/// The classes of quality_color, each coloured by quality_color itself.
std::vector<LegendEntry> quality_legend() {
    auto of = [](ScanRowState state, std::optional<double> rms_mm) {
        return quality_color({.state = state, .rms_mm = rms_mm});
    };
    return {{.color = of(ScanRowState::kRegistered, 0.2), .label = "RMS < 0.5 mm"},
            {.color = of(ScanRowState::kRegistered, 1.0), .label = "RMS 0.5-1.5 mm"},
            {.color = of(ScanRowState::kRegistered, 2.0), .label = "RMS > 1.5 mm"},
            {.color = of(ScanRowState::kUnjoined, std::nullopt), .label = "unjoined"},
            {.color = of(ScanRowState::kFlagged, std::nullopt), .label = "contradicts"},
            {.color = of(ScanRowState::kFailed, std::nullopt), .label = "failed"}};
}

void draw_scale_bar(ImDrawList& draw, const ScaleBar& bar, ImVec2 left) {
    const ImU32 white = IM_COL32(235, 235, 235, 255);
    const ImVec2 right(left.x + bar.length_px, left.y);
    draw.AddLine(left, right, white, 2.0f);
    draw.AddLine(ImVec2(left.x, left.y - 5), ImVec2(left.x, left.y + 5), white, 2.0f);
    draw.AddLine(ImVec2(right.x, right.y - 5), ImVec2(right.x, right.y + 5), white, 2.0f);
    const ImVec2 size = ImGui::CalcTextSize(bar.label.c_str());
    draw.AddText(ImVec2(left.x + 0.5f * (bar.length_px - size.x), left.y - size.y - 6), white,
                 bar.label.c_str());
}

void draw_axes(ImDrawList& draw, const OrbitCamera& camera, ImVec2 origin, float length_px) {
    const std::array<ImU32, 3> colors{IM_COL32(240, 70, 60, 255), IM_COL32(80, 220, 90, 255),
                                      IM_COL32(90, 140, 255, 255)};
    const auto axes = axes_on_screen(camera);
    for (std::size_t i = 0; i < 3; ++i) {
        const ImVec2 tip(origin.x + length_px * static_cast<float>(axes[i].x()),
                         origin.y + length_px * static_cast<float>(axes[i].y()));
        draw.AddLine(origin, tip, colors[i], 2.0f);
        const char name[2] = {static_cast<char>('X' + i), '\0'};
        draw.AddText(ImVec2(tip.x + 2, tip.y - 7), colors[i], name);
    }
}

void draw_legend(ImDrawList& draw, const FieldViewState& state, ImVec2 bottom_right) {
    const std::vector<LegendEntry> entries = color_legend(state);
    const char* title =
        state.view_mode == ViewMode::kMesh ? "Mesh surface" : legend_title(state.color_mode);
    const float line = ImGui::GetTextLineHeightWithSpacing();
    float width = ImGui::CalcTextSize(title).x;
    for (const LegendEntry& e : entries)
        width = std::max(width, ImGui::CalcTextSize(e.label.c_str()).x + line);
    const float height = line * static_cast<float>(entries.size() + 1);
    ImVec2 at(bottom_right.x - width - 8, bottom_right.y - height - 8);
    draw.AddRectFilled(ImVec2(at.x - 6, at.y - 4), ImVec2(bottom_right.x - 2, bottom_right.y - 4),
                       IM_COL32(20, 22, 28, 200), 4.0f);
    draw.AddText(at, IM_COL32(235, 235, 235, 255), title);
    for (const LegendEntry& e : entries) {
        at.y += line;
        const ImVec2 centre(at.x + 0.4f * line, at.y + 0.5f * line);
        if (e.ring)
            draw.AddCircle(centre, 0.32f * line, to_imgui(e.color), 0, 2.0f);
        else
            draw.AddCircleFilled(centre, 0.3f * line, to_imgui(e.color));
        draw.AddText(ImVec2(at.x + line, at.y), IM_COL32(235, 235, 235, 255), e.label.c_str());
    }
}

}  // namespace

ScaleBar scale_bar(double metres_per_px, float max_px) {
    if (!(metres_per_px > 0.0) || !(max_px > 0.0f)) return {};
    const double max_m = metres_per_px * max_px;
    const double decade = std::pow(10.0, std::floor(std::log10(max_m)));
    double length_m = decade;
    for (const double step : {2.0, 5.0})
        if (step * decade <= max_m) length_m = step * decade;
    return {.length_m = length_m,
            .length_px = static_cast<float>(length_m / metres_per_px),
            .label = length_label(length_m)};
}

double metres_per_px_at_target(const OrbitCamera& camera, float view_height_px) {
    if (view_height_px <= 0.0f) return 0.0;
    return 2.0 * camera.distance_m() * std::tan(0.5 * camera.fov_y_rad()) / view_height_px;
}

std::array<Eigen::Vector2d, 3> axes_on_screen(const OrbitCamera& camera) {
    const Eigen::Matrix3d R = camera.view().linear();  // world → camera (y up)
    std::array<Eigen::Vector2d, 3> axes;
    for (int i = 0; i < 3; ++i) {
        const Eigen::Vector3d d = R.col(i);
        axes[static_cast<std::size_t>(i)] = Eigen::Vector2d(d.x(), -d.y());  // screen y down
    }
    return axes;
}

std::vector<LegendEntry> color_legend(const FieldViewState& state, std::size_t max_scans) {
    if (state.view_mode == ViewMode::kMesh)
        return {{.color = surface_class_color(SurfaceClass::kMeasured), .label = "measured"},
                {.color = surface_class_color(SurfaceClass::kInterpolated),
                 .label = "interpolated (never seen)"}};
    switch (state.color_mode) {
        case ColorMode::kByScan:
            return scan_legend(state, max_scans);
        case ColorMode::kByQuality:
            return quality_legend();
        case ColorMode::kByCoverage:
            break;
    }
    return {{.color = {150, 150, 150}, .label = "points as scanned"},
            {.color = coverage_sample_color(SampleState::kUnobserved),
             .label = "hole (unobserved)",
             .ring = true}};
}

const char* legend_title(ColorMode mode) {
    switch (mode) {
        case ColorMode::kByScan:
            return "Colour by scan";
        case ColorMode::kByQuality:
            return "Colour by registration";
        case ColorMode::kByCoverage:
            break;
    }
    return "Coverage";
}

void draw_view_overlay(const FieldViewState& state, const OrbitCamera& camera,
                       const OverlayRect& view) {
    ImDrawList& draw = *ImGui::GetBackgroundDrawList();
    const float bottom = view.y_px + view.height_px - 12.0f;
    const float axes_px = 40.0f;
    draw_axes(draw, camera, ImVec2(view.x_px + 14 + axes_px, bottom - axes_px), axes_px);
    const ScaleBar bar =
        scale_bar(metres_per_px_at_target(camera, view.height_px), 0.3f * view.width_px);
    if (bar.length_px > 0.0f)
        draw_scale_bar(draw, bar, ImVec2(view.x_px + 40 + 2 * axes_px, bottom - 4));
    draw_legend(draw, state, ImVec2(view.x_px + view.width_px, view.y_px + view.height_px));
}

}  // namespace anascan::gui
