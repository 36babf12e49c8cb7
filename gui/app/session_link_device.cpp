// The device panel's link to the session's device: connect, read and apply its settings,
// and the live camera preview grabbed between captures (CaptureSession's device calls run
// on its scanner thread, so never during a capture; the UI thread only polls futures).
#include <fmt/format.h>

#include "session_link.hpp"

namespace anascan::field {
namespace {

/// Each camera image of the preview at most this wide (two side by side in the panel).
constexpr int kCameraPreviewWidthPx = 320;
/// Between two preview grabs, and after a capture before the first.
constexpr auto kCameraGrabInterval = std::chrono::milliseconds(500);
constexpr auto kCameraGrabAfterCapture = std::chrono::seconds(1);
constexpr auto kCameraRetryAfterError = std::chrono::seconds(2);

template <typename T>
bool ready(const std::optional<std::future<T>>& future) {
    return future && future->wait_for(std::chrono::seconds(0)) == std::future_status::ready;
}

}  // namespace

/// Opens the session for capture (if it is not) and attaches the active device; its
/// settings are then read by poll_device.
void SessionLink::open_device(gui::FieldViewState& view) {
    const int device = view.device.active_device;
    if (device < 0 || device >= static_cast<int>(view.device.devices.size())) {
        view.status.last_error = "no device chosen: pick one in the device panel";
        return;
    }
    if (!session_ && !start_session(view)) return;
    (void)attach(view.device.devices[static_cast<std::size_t>(device)].id, view);
}

void SessionLink::apply_settings(gui::FieldViewState& view) {
    gui::DeviceSettingsState& st = view.device.settings;
    if (!session_ || attached_uri_.empty() || pending_settings_) return;
    for (const acquisition::DeviceSetting& s : st.edited.settings) {
        if (std::string problem = gui::setting_problem(s); !problem.empty()) {
            st.message = "Not applied: " + problem;
            st.message_is_error = true;
            return;
        }
    }
    pending_settings_ = session_->apply_device_settings(st.edited);
    settings_applying_ = true;
    st.busy = true;
}

void SessionLink::poll_device(gui::FieldViewState& view) {
    gui::DevicePanelState& device = view.device;
    if (!attached_uri_.empty() && !device.connected && session_) {
        device.connected = true;  // attached (by "Connect" or the first capture): read it
        pending_settings_ = session_->device_settings();
        device.settings.busy = true;
        cameras_wanted_ = cameras_due_ = true;
    }
    if (ready(pending_settings_)) take_settings(device);
    if (captures_seen_ != captures_finished_) {  // a capture ended: a fresh view is due
        captures_seen_ = captures_finished_;
        cameras_due_ = true;
        next_camera_grab_ = std::chrono::steady_clock::now() + kCameraGrabAfterCapture;
    }
    poll_cameras(device);
}

void SessionLink::take_settings(gui::DevicePanelState& device) {
    gui::DeviceSettingsState& st = device.settings;
    Expected<acquisition::DeviceSettingsForm> form = pending_settings_->get();
    pending_settings_.reset();
    st.busy = false;
    const bool applied = std::exchange(settings_applying_, false);
    if (!form) {
        st.message =
            (applied ? "Not applied: " : "Cannot read the settings: ") + form.error().message;
        st.message_is_error = true;
        return;
    }
    st.applied = st.edited = std::move(*form);
    st.message = applied ? "Applied; recorded in the session (next scans use them)" : "";
    st.message_is_error = false;
}

/// A grab whenever the scanner thread is free (no capture, no settings call) and the last
/// image is older than the interval; its images go to the panel's textures.
void SessionLink::poll_cameras(gui::DevicePanelState& device) {
    const auto now = std::chrono::steady_clock::now();
    if (ready(pending_cameras_)) {
        Expected<acquisition::CameraPreview> preview = pending_cameras_->get();
        pending_cameras_.reset();
        cameras_due_ = false;
        if (preview) {
            camera_textures_.show(*preview, device);
            cameras_wanted_ = !preview->images.empty();
            next_camera_grab_ = std::max(next_camera_grab_, now + kCameraGrabInterval);
        } else {
            device.cameras.clear();
            device.cameras_caption = "No camera view: " + preview.error().message;
            next_camera_grab_ = now + kCameraRetryAfterError;
        }
    }
    if (!cameras_wanted_ || !session_ || attached_uri_.empty() || pending_capture_ ||
        pending_cameras_ || pending_settings_ || now < next_camera_grab_)
        return;
    pending_cameras_ = session_->preview_cameras(kCameraPreviewWidthPx);
}

}  // namespace anascan::field
