#include "anascan/gui/ui_action.hpp"

namespace anascan::gui {

bool apply_view_action(FieldViewState& state, const UiAction& action) {
    switch (action.kind) {
        case UiActionKind::kSelectScan:
            state.selected_seq = action.seq;
            return true;
        case UiActionKind::kSetColorMode:
            state.color_mode = action.color_mode;
            return true;
        case UiActionKind::kToggleContrast:
            state.high_contrast = !state.high_contrast;
            return true;
        default:
            return false;
    }
}

}  // namespace anascan::gui
