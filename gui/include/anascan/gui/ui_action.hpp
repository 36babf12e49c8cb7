#pragma once
/// \file
/// What the operator asked for, returned by the panels as values. The app applies the
/// view-only ones itself (apply_view_action) and forwards the others to the session.

#include <cstdint>
#include <string>
#include <vector>

#include "anascan/gui/field_view_state.hpp"

namespace anascan::gui {

enum class UiActionKind {
    kSelectScan,      ///< seq: highlight this scan (view only).
    kCapture,         ///< Capture a scan with the active device.
    kExclude,         ///< seq: leave the scan out of the model (undoable).
    kInclude,         ///< seq: undo an exclusion.
    kReRegister,      ///< seq: register the scan again.
    kTurnedOver,      ///< The stone was turned over before the next scan.
    kConnectDevice,   ///< device_index: connect (or choose) this device.
    kSetColorMode,    ///< color_mode (view only).
    kToggleContrast,  ///< Switch the high-contrast theme (view only).
    kFitView,         ///< Fit the camera to the stone (view only).
    kOpenDevice,      ///< Connect the active device: read its settings, preview its cameras.
    kEditSetting,     ///< setting_index, value: the operator typed a setting (view only).
    kApplySettings,   ///< Apply the edited settings to the device.
    kRevertSettings,  ///< Forget the edits: back to the settings in effect (view only).
    kMakeMesh,        ///< Make the fragment model of the view's group (in the background).
    kSetViewMode,     ///< view_mode: points or mesh (view only; mesh once one is ready).
    kTogglePair,      ///< text: choose or drop the face pair "A:F=B:G" (assembly view).
    kToggleCoplanar,  ///< text: make faces "A:F=B:G" co-planar, or no longer (assembly view).
    kPickFace,        ///< text: face "A:F" clicked in the view (assembly view; "" clears).
    kAlignBlocks,     ///< Align the blocks by the chosen pairs (in the background).
    kAcceptAssembly,  ///< Keep the alignment: write the assembly folder.
};

/// One operator request.
struct UiAction {
    UiActionKind kind = UiActionKind::kCapture;
    std::int64_t seq = -1;                      ///< For the scan actions.
    int device_index = -1;                      ///< For kConnectDevice.
    ColorMode color_mode = ColorMode::kByScan;  ///< For kSetColorMode.
    ViewMode view_mode = ViewMode::kPoints;     ///< For kSetViewMode.
    int setting_index = -1;                     ///< For kEditSetting: into the form.
    double value = 0.0;                         ///< For kEditSetting: number, or choice index.
    std::string text;                           ///< For kTogglePair, kToggleCoplanar, kPickFace.
    friend bool operator==(const UiAction&, const UiAction&) = default;
};

using UiActions = std::vector<UiAction>;

/// Applies a view-only action (select, colour mode, contrast) to the state; returns false
/// for actions that must go to the session (capture, exclude, ...) or the camera (fit).
bool apply_view_action(FieldViewState& state, const UiAction& action);

}  // namespace anascan::gui
