#pragma once
/// \file
/// The device panel's link to the session's device once attached: read and apply its
/// settings, and the live camera preview grabbed between captures. CaptureSession's
/// device calls run on its scanner thread, so never during a capture; the UI thread only
/// polls futures. UI thread only.

#include <chrono>
#include <future>
#include <optional>

#include "anascan/acquisition/capture/capture_session.hpp"
#include "anascan/gui/field_view_state.hpp"
#include "preview_texture.hpp"

namespace anascan::field {

/// What the device link needs to know of the session this frame.
struct DeviceLinkInputs {
    acquisition::CaptureSession* session = nullptr;  ///< Null until opened for capture.
    bool attached = false;                           ///< The device is attached.
    bool capturing = false;                          ///< A capture is in flight.
    int captures_finished = 0;
};

class DeviceLink {
public:
    /// Applies the edited settings on the device (each value checked first).
    void apply_settings(const DeviceLinkInputs& in, gui::DeviceSettingsState& settings);
    /// Once per frame: reads the settings once attached, takes answers, grabs cameras.
    void poll(const DeviceLinkInputs& in, gui::DevicePanelState& device);
    /// No settings call pending, no camera preview due.
    bool settled() const { return !pending_settings_ && !(cameras_wanted_ && cameras_due_); }

private:
    void take_settings(gui::DevicePanelState& device);
    void poll_cameras(const DeviceLinkInputs& in, gui::DevicePanelState& device);

    CameraTextures camera_textures_;
    bool settings_applying_ = false;  ///< pending_settings_ is an apply (not a read).
    bool cameras_wanted_ = false;     ///< The device has cameras (until a preview says none).
    bool cameras_due_ = false;        ///< No preview since the device was attached or captured.
    int captures_seen_ = 0;
    std::chrono::steady_clock::time_point next_camera_grab_{};
    std::optional<std::future<Expected<acquisition::DeviceSettingsForm>>> pending_settings_;
    std::optional<std::future<Expected<acquisition::CameraPreview>>> pending_cameras_;
};

}  // namespace anascan::field
