#include "anascan/gui/panels.hpp"
#include "panel_util.hpp"

namespace anascan::gui {
namespace {

ColorMode next_color_mode(ColorMode mode) {
    switch (mode) {
        case ColorMode::kByScan:
            return ColorMode::kByQuality;
        case ColorMode::kByQuality:
            return ColorMode::kByCoverage;
        case ColorMode::kByCoverage:
            return ColorMode::kByScan;
    }
    return ColorMode::kByScan;
}

}  // namespace

void handle_shortcuts(const FieldViewState& state, UiActions& actions) {
    if (ImGui::GetIO().WantTextInput) return;
    const bool no_repeat = false;
    if (ImGui::IsKeyPressed(kKeyCapture, no_repeat) && state.device.active_device >= 0 &&
        !state.device.capturing) {
        actions.push_back({.kind = UiActionKind::kCapture});
    }
    if (ImGui::IsKeyPressed(kKeyExcludeLast, no_repeat)) {
        const std::int64_t seq = newest_scan(state);
        if (seq >= 0) actions.push_back({.kind = UiActionKind::kExclude, .seq = seq});
    }
    if (ImGui::IsKeyPressed(kKeyTurnedOver, no_repeat)) {
        actions.push_back({.kind = UiActionKind::kTurnedOver});
    }
    if (ImGui::IsKeyPressed(kKeyFitView, no_repeat)) {
        actions.push_back({.kind = UiActionKind::kFitView});
    }
    if (ImGui::IsKeyPressed(kKeyColorMode, no_repeat)) {
        actions.push_back(
            {.kind = UiActionKind::kSetColorMode, .color_mode = next_color_mode(state.color_mode)});
    }
    if (ImGui::IsKeyPressed(kKeyMakeMesh, no_repeat) &&
        state.mesh.status != MeshViewState::Status::kMaking) {
        actions.push_back({.kind = UiActionKind::kMakeMesh});
    }
    if (ImGui::IsKeyPressed(kKeyViewMode, no_repeat) &&
        state.mesh.status == MeshViewState::Status::kReady) {
        actions.push_back({.kind = UiActionKind::kSetViewMode,
                           .view_mode = state.view_mode == ViewMode::kMesh ? ViewMode::kPoints
                                                                           : ViewMode::kMesh});
    }
}

void draw_field_panels(const FieldViewState& state, const PanelLayout& layout, UiActions& actions) {
    draw_scan_list(state, layout, actions);
    draw_device_panel(state, layout, actions);
    draw_status_bar(state, layout);
    draw_failure_banner(state, layout, actions);
    handle_shortcuts(state, actions);
}

}  // namespace anascan::gui
