#include "anascan/gui/ui_action.hpp"

namespace anascan::gui {
namespace {

void edit_setting(acquisition::DeviceSettingsForm& form, const UiAction& action) {
    if (action.setting_index < 0 || action.setting_index >= static_cast<int>(form.settings.size()))
        return;
    acquisition::DeviceSetting& s = form.settings[static_cast<std::size_t>(action.setting_index)];
    if (s.kind == acquisition::DeviceSettingKind::kNumber)
        s.value = action.value;
    else
        s.choice = static_cast<int>(action.value);
}

}  // namespace

bool apply_view_action(FieldViewState& state, const UiAction& action) {
    switch (action.kind) {
        case UiActionKind::kSelectScan:
            state.selected_seq = action.seq;
            return true;
        case UiActionKind::kSetColorMode:
            state.color_mode = action.color_mode;
            return true;
        case UiActionKind::kSetViewMode:
            if (action.view_mode == ViewMode::kPoints ||
                state.mesh.status == MeshViewState::Status::kReady)
                state.view_mode = action.view_mode;
            return true;
        case UiActionKind::kToggleContrast:
            state.high_contrast = !state.high_contrast;
            return true;
        case UiActionKind::kEditSetting:
            edit_setting(state.device.settings.edited, action);
            return true;
        case UiActionKind::kRevertSettings:
            state.device.settings.edited = state.device.settings.applied;
            state.device.settings.message.clear();
            return true;
        default:
            return false;
    }
}

}  // namespace anascan::gui
