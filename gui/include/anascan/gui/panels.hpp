#pragma once
/// \file
/// The field app's panels: each draws one ImGui window from explicit state and appends the
/// operator's requests to `actions`. No panel keeps state of its own, so a panel drawn
/// twice from the same state and input draws the same thing. Call between
/// ImGui::NewFrame() and ImGui::Render(); not thread-safe (ImGui's context is global).

#include "anascan/gui/field_view_state.hpp"
#include "anascan/gui/ui_action.hpp"

namespace anascan::gui {

/// The scan list, the device panel and the status bar draw no window background (Mesa's
/// llvmpipe spends about as long on ImGui's blended, textured background quads as on all
/// the rest of a frame): the app clears the window with ImGuiCol_WindowBg first
/// (`panel_background()`), which costs next to nothing. The banner draws its own.
struct PanelBackground {
    float r = 0.0f, g = 0.0f, b = 0.0f;
};
/// The colour to clear the window with: the style's window background (over black when
/// translucent). Needs a current ImGui context.
PanelBackground panel_background();

/// Where the panels go, in pixels of the main window (origin top left).
struct PanelLayout {
    float width_px = 1280.0f;
    float height_px = 800.0f;
    float scan_list_width_px = 450.0f;  ///< The scan list, on the left.
    float device_width_px = 360.0f;     ///< The device panel, on the right.
    float status_height_px = 40.0f;
    float banner_height_px = 90.0f;

    /// The 3D view: between the side panels, above the status bar (x, y from top left).
    float view_x_px() const { return scan_list_width_px; }
    float view_width_px() const { return width_px - scan_list_width_px - device_width_px; }
    float view_height_px() const { return height_px - status_height_px; }
};

/// The scan list window ("Scans"): one row per scan in capture order; clicking a row
/// selects it; the selected row offers exclude / include / re-register.
void draw_scan_list(const FieldViewState& state, const PanelLayout& layout, UiActions& actions);

/// The status bar window ("Status"): coverage %, queued registrations, free disk, last
/// error.
void draw_status_bar(const FieldViewState& state, const PanelLayout& layout);

/// The device panel window ("Device"): devices with connect buttons, the capture and
/// turned-over buttons, the live camera preview, the device's settings, the colour mode and
/// theme switches, the last scan as the scanner saw it.
void draw_device_panel(const FieldViewState& state, const PanelLayout& layout, UiActions& actions);

/// Inside the device panel: "Connect" until the device is attached, then its settings as
/// editable fields (number with unit and range, or a choice), each out-of-range value in
/// red with the allowed range, "Apply settings" (only with valid changes) and "Revert",
/// and the device's answer to the last apply (device_settings_panel.cpp).
void draw_device_settings(const DevicePanelState& device, UiActions& actions);

/// Inside the device panel: the cameras' latest images side by side (in the child window
/// kCameraPreviewChild), with their time.
void draw_camera_preview(const DevicePanelState& device);
inline constexpr const char* kCameraPreviewChild = "Cameras";

/// The banner over the view, drawn only when session_banner(state) has a value: a failed
/// capture ("Capture failed", red), a failed registration ("Registration failed", red) or
/// a split model ("Model split", amber),
/// large, with the message, what to try and an exclude button for the scan at fault.
/// Returns true when drawn.
bool draw_failure_banner(const FieldViewState& state, const PanelLayout& layout,
                         UiActions& actions);

/// Keyboard shortcuts (ignored while a text field has focus): Space = capture,
/// X = exclude the newest scan, T = turned over, F = fit view, C = cycle colour mode,
/// M = make the mesh, V = switch between points and mesh.
void handle_shortcuts(const FieldViewState& state, UiActions& actions);

/// Key indices of the shortcuts in ImGuiIO::KeysDown (GLFW key codes, which are ASCII for
/// letters and space).
inline constexpr int kKeyCapture = 32;  // Space
inline constexpr int kKeyExcludeLast = 'X';
inline constexpr int kKeyTurnedOver = 'T';
inline constexpr int kKeyFitView = 'F';
inline constexpr int kKeyColorMode = 'C';
inline constexpr int kKeyMakeMesh = 'M';
inline constexpr int kKeyViewMode = 'V';

/// Draws every panel (banner, scan list, device panel, status bar) and the shortcuts.
void draw_field_panels(const FieldViewState& state, const PanelLayout& layout, UiActions& actions);

}  // namespace anascan::gui
