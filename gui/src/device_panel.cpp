#include <fmt/format.h>

#include <algorithm>

#include "anascan/gui/panels.hpp"
#include "panel_util.hpp"

namespace anascan::gui {
namespace {

void draw_devices(const DevicePanelState& device, UiActions& actions) {
    if (device.devices.empty()) ImGui::TextColored(detail::kColorMuted, "No devices found");
    for (int i = 0; i < static_cast<int>(device.devices.size()); ++i) {
        const DeviceRow& row = device.devices[static_cast<std::size_t>(i)];
        const bool active = i == device.active_device;
        ImGui::TextColored(row.connected ? detail::kColorGood : detail::kColorBad, "%s%s",
                           active ? "> " : "  ", row.id.c_str());
        ImGui::SameLine();
        const std::string label = fmt::format("{}##dev{}", row.connected ? "Use" : "Connect", i);
        if (!active && ImGui::SmallButton(label.c_str())) {
            actions.push_back({.kind = UiActionKind::kConnectDevice, .device_index = i});
        }
        ImGui::TextColored(detail::kColorMuted, "    %s, %s", row.kind.c_str(), row.status.c_str());
    }
}

void draw_capture_buttons(const DevicePanelState& device, UiActions& actions) {
    const bool can_capture = device.active_device >= 0 && !device.capturing;
    ImGui::BeginDisabled(!can_capture);
    const float width = ImGui::GetContentRegionAvail().x;
    if (ImGui::Button(device.capturing ? "Capturing..." : "Capture  (Space)",
                      ImVec2(width, 2.5f * ImGui::GetFrameHeight()))) {
        actions.push_back({.kind = UiActionKind::kCapture});
    }
    ImGui::EndDisabled();
    if (ImGui::Button("Stone turned over  (T)", ImVec2(width, 0.0f))) {
        actions.push_back({.kind = UiActionKind::kTurnedOver});
    }
}

/// The last scan as the scanner saw it: as wide as the panel, at most half as high.
void draw_preview(const DevicePanelState& device) {
    if (device.preview_texture == 0 || device.preview_width_px <= 0) return;
    const float avail = ImGui::GetContentRegionAvail().x;
    const float aspect =
        static_cast<float>(device.preview_height_px) / static_cast<float>(device.preview_width_px);
    const float height = std::min(avail * aspect, 0.5f * avail);
    ImGui::Image(reinterpret_cast<ImTextureID>(device.preview_texture),
                 ImVec2(height / aspect, height));
    ImGui::PushStyleColor(ImGuiCol_Text, detail::kColorMuted);
    ImGui::TextWrapped("%s", device.preview_caption.c_str());
    ImGui::PopStyleColor();
}

void draw_view_options(const FieldViewState& state, UiActions& actions) {
    ImGui::TextUnformatted("Colour points by");
    constexpr std::pair<ColorMode, const char*> kModes[] = {{ColorMode::kByScan, "scan"},
                                                            {ColorMode::kByQuality, "quality"},
                                                            {ColorMode::kByCoverage, "coverage"}};
    for (const auto& [mode, name] : kModes) {
        if (ImGui::RadioButton(name, state.color_mode == mode)) {
            actions.push_back({.kind = UiActionKind::kSetColorMode, .color_mode = mode});
        }
    }
    bool high_contrast = state.high_contrast;
    if (ImGui::Checkbox("High contrast", &high_contrast)) {
        actions.push_back({.kind = UiActionKind::kToggleContrast});
    }
    if (ImGui::Button("Fit view  (F)")) actions.push_back({.kind = UiActionKind::kFitView});
}

/// Points or mesh, the mesh button and what the mesh is (or why there is none).
void draw_mesh_options(const FieldViewState& state, UiActions& actions) {
    const MeshViewState& mesh = state.mesh;
    const bool making = mesh.status == MeshViewState::Status::kMaking;
    ImGui::BeginDisabled(making);
    const char* label = mesh.status == MeshViewState::Status::kReady ? "Make the mesh again  (M)"
                                                                     : "Make the mesh  (M)";
    if (ImGui::Button(label)) actions.push_back({.kind = UiActionKind::kMakeMesh});
    ImGui::EndDisabled();
    if (mesh.status == MeshViewState::Status::kReady) {
        ImGui::TextUnformatted("Show");
        for (const auto& [mode, name] :
             {std::pair{ViewMode::kPoints, "points"}, std::pair{ViewMode::kMesh, "mesh  (V)"}}) {
            ImGui::SameLine();
            if (ImGui::RadioButton(name, state.view_mode == mode))
                actions.push_back({.kind = UiActionKind::kSetViewMode, .view_mode = mode});
        }
    }
    const std::string summary = mesh_summary(mesh);
    if (summary.empty()) return;
    const bool bad = mesh.status == MeshViewState::Status::kFailed || !mesh.outdated.empty();
    ImGui::PushStyleColor(ImGuiCol_Text, bad ? detail::kColorWarn : detail::kColorMuted);
    ImGui::TextWrapped("%s", summary.c_str());
    ImGui::PopStyleColor();
}

}  // namespace

void draw_device_panel(const FieldViewState& state, const PanelLayout& layout, UiActions& actions) {
    detail::place_next_window(layout.width_px - layout.device_width_px, 0.0f,
                              layout.device_width_px, layout.height_px - layout.status_height_px);
    ImGui::Begin("Device", nullptr, detail::kClearedPanelFlags);
    if (!state.session_dir.empty()) {
        ImGui::TextWrapped("Session: %s", state.session_dir.c_str());
    }
    if (!state.session_check.empty()) {
        ImGui::TextColored(detail::kColorWarn, "%s", state.session_check.c_str());
    }
    ImGui::Separator();
    draw_devices(state.device, actions);
    ImGui::Separator();
    draw_capture_buttons(state.device, actions);
    draw_camera_preview(state.device);  // right under the buttons: aiming the scanner
    ImGui::Separator();
    draw_device_settings(state.device, actions);
    ImGui::Separator();
    draw_view_options(state, actions);
    draw_mesh_options(state, actions);
    ImGui::TextWrapped("X excludes the newest scan, C cycles the colours.");
    draw_preview(state.device);  // last: the buttons above stay in view
    ImGui::End();
}

}  // namespace anascan::gui
