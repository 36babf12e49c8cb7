#include "state_dump.hpp"

#include <fstream>
#include <nlohmann/json.hpp>

namespace anascan::field {
namespace {

const char* state_name(gui::ScanRowState state) {
    switch (state) {
        case gui::ScanRowState::kQueued:
            return "queued";
        case gui::ScanRowState::kRegistered:
        case gui::ScanRowState::kUnjoined:  // registered in acquisition's terms
            return "registered";
        case gui::ScanRowState::kFailed:
            return "failed";
        case gui::ScanRowState::kExcluded:
            return "excluded";
        case gui::ScanRowState::kFlagged:
            return "flagged";
    }
    return "queued";
}

const char* banner_kind_name(gui::BannerKind kind) {
    switch (kind) {
        case gui::BannerKind::kCaptureFailed:
            return "capture-failed";
        case gui::BannerKind::kFailed:
            return "registration-failed";
        case gui::BannerKind::kSplit:
            return "split";
        case gui::BannerKind::kDisagree:
            return "disagree";
    }
    return "?";
}

template <typename T>
nlohmann::json optional_json(const std::optional<T>& value) {
    return value ? nlohmann::json(*value) : nlohmann::json(nullptr);
}

nlohmann::json scans_json(const gui::FieldViewState& view) {
    nlohmann::json scans = nlohmann::json::array();
    for (const gui::ScanRow& row : view.scans) {
        scans.push_back({{"seq", row.seq},
                         {"device_id", row.device_id},
                         {"state", state_name(row.state)},
                         {"list_state", gui::to_string(row.state)},
                         {"group", row.group},
                         {"rms_mm", optional_json(row.rms_mm)},
                         {"overlap_percent", optional_json(row.overlap_percent)},
                         {"message", row.message}});
    }
    return scans;
}

nlohmann::json devices_json(const gui::FieldViewState& view) {
    nlohmann::json devices = nlohmann::json::array();
    for (const gui::DeviceRow& d : view.device.devices) {
        devices.push_back(
            {{"id", d.id}, {"kind", d.kind}, {"connected", d.connected}, {"status", d.status}});
    }
    return devices;
}

nlohmann::json device_settings_json(const gui::DevicePanelState& device) {
    nlohmann::json fields = nlohmann::json::array();
    for (const acquisition::DeviceSetting& s : device.settings.applied.settings) {
        nlohmann::json field{{"key", s.key}, {"label", s.label}, {"unit", s.unit}};
        if (s.kind == acquisition::DeviceSettingKind::kNumber) {
            field["value"] = s.value;
            field["min"] = s.min;
            field["max"] = s.max;
        } else {
            field["choices"] = s.choices;
            field["choice"] = s.choice;
        }
        fields.push_back(std::move(field));
    }
    return {{"connected", device.connected},
            {"device", device.settings.applied.device},
            {"applied", std::move(fields)},
            {"message", device.settings.message},
            {"message_is_error", device.settings.message_is_error}};
}

nlohmann::json cameras_json(const gui::DevicePanelState& device,
                            const std::optional<std::array<float, 4>>& rect) {
    nlohmann::json cameras = nlohmann::json::array();
    for (const gui::CameraPreviewView& c : device.cameras)
        cameras.push_back({{"name", c.name}, {"width_px", c.width_px}, {"height_px", c.height_px}});
    return {{"images", std::move(cameras)},
            {"caption", device.cameras_caption},
            {"rect", rect ? nlohmann::json(*rect) : nlohmann::json(nullptr)}};
}

const char* mesh_status_name(gui::MeshViewState::Status status) {
    switch (status) {
        case gui::MeshViewState::Status::kNone:
            return "none";
        case gui::MeshViewState::Status::kMaking:
            return "making";
        case gui::MeshViewState::Status::kReady:
            return "ready";
        case gui::MeshViewState::Status::kFailed:
            return "failed";
    }
    return "?";
}

nlohmann::json mesh_json(const gui::FieldViewState& view, std::size_t triangles_drawn) {
    const gui::MeshViewState& m = view.mesh;
    return {{"status", mesh_status_name(m.status)},
            {"message", m.message},
            {"summary", gui::mesh_summary(m)},
            {"shown", view.view_mode == gui::ViewMode::kMesh},
            {"resolution_mm", m.resolution_mm},
            {"scans", m.scans},
            {"triangles", m.triangles},
            {"triangles_on_gpu", triangles_drawn},
            {"area_m2", m.area_m2},
            {"interpolated_share", m.interpolated_share},
            {"closed", m.closed},
            {"seconds", m.seconds},
            {"outdated", m.outdated}};
}

Expected<void> write_json(const std::filesystem::path& file, const nlohmann::json& doc) {
    std::ofstream out(file);
    out << doc.dump(2) << "\n";
    out.close();
    if (!out) return fail(ErrorCode::kIo, file.string() + ": cannot write the state file");
    return {};
}

}  // namespace

Expected<void> write_state_json(const std::filesystem::path& file, const gui::FieldViewState& view,
                                const ViewFigures& figures) {
    const auto banner = gui::session_banner(view);
    const auto& status = view.status;
    const nlohmann::json doc{
        {"session", view.session_dir},
        {"session_check", view.session_check},
        {"scans", scans_json(view)},
        {"coverage_percent", optional_json(status.coverage_percent)},
        {"coverage_fraction", status.coverage_percent
                                  ? nlohmann::json(*status.coverage_percent / 100.0)
                                  : nlohmann::json(nullptr)},
        {"queued_registrations", status.queued_registrations},
        {"disk_free_bytes", optional_json(status.disk_free_bytes)},
        {"last_error", status.last_error},
        {"banner", banner ? nlohmann::json(banner->message) : nlohmann::json(nullptr)},
        {"banner_details", banner ? nlohmann::json(banner->details) : nlohmann::json(nullptr)},
        {"banner_kind",
         banner ? nlohmann::json(banner_kind_name(banner->kind)) : nlohmann::json(nullptr)},
        {"devices", devices_json(view)},
        {"active_device", view.device.active_device},
        {"preview",
         {{"shown", view.device.preview_texture != 0},
          {"width_px", view.device.preview_width_px},
          {"height_px", view.device.preview_height_px},
          {"caption", view.device.preview_caption}}},
        {"device_settings", device_settings_json(view.device)},
        {"camera_preview", cameras_json(view.device, figures.camera_preview_rect)},
        {"mesh", mesh_json(view, figures.mesh_triangles)},
        {"points_total", figures.points_total},
        {"chunks", figures.chunks}};
    return write_json(file, doc);
}

Expected<void> write_assembly_state_json(const std::filesystem::path& file,
                                         const gui::AssemblyViewState& v,
                                         const AssemblyFigures& figures) {
    using nlohmann::json;
    json report = nullptr;
    if (v.report) {
        json pairs = json::array();
        for (const auto& p : v.report->pairs)
            pairs.push_back({{"pair", p.pair},
                             {"gap_median_mm", p.gap_median_mm},
                             {"gap_p95_mm", p.gap_p95_mm},
                             {"gap_min_mm", p.gap_min_mm}});
        json coplanar = json::array();
        for (const auto& c : v.report->coplanar)
            coplanar.push_back(
                {{"pair", c.pair}, {"angle_deg", c.angle_deg}, {"offset_mm", c.offset_mm}});
        report = {{"status", v.report->status},
                  {"coplanar", coplanar},
                  {"iterations", v.report->iterations},
                  {"offending", v.report->offending},
                  {"penetration_max_mm", v.report->penetration_max_mm},
                  {"pairs", pairs}};
    }
    json blocks = json::array();
    for (const auto& b : v.blocks) blocks.push_back({{"id", b.id}, {"fixed", b.fixed}});
    const json out{{"folder", v.folder},
                   {"phase", gui::to_string(v.phase)},
                   {"blocks", blocks},
                   {"proposal_faces", v.proposals.size()},
                   {"chosen_pairs", v.chosen_pairs},
                   {"chosen_coplanar", v.chosen_coplanar},
                   {"picked_face", v.picked_face},
                   {"report", report},
                   {"saved_to", v.saved_to},
                   {"last_error", v.last_error},
                   {"points_total", figures.points_total},
                   {"frames_while_busy", figures.busy_frames},
                   {"longest_busy_frame_ms", figures.busy_frame_max_ms}};
    return write_json(file, out);
}

}  // namespace anascan::field
