#include "device_link.hpp"

#include "future_ready.hpp"

namespace anascan::field {
namespace {

/// Each camera image of the preview at most this wide (two side by side in the panel).
constexpr int kCameraPreviewWidthPx = 320;
/// Between two preview grabs, and after a capture before the first.
constexpr auto kCameraGrabInterval = std::chrono::milliseconds(500);
constexpr auto kCameraGrabAfterCapture = std::chrono::seconds(1);
constexpr auto kCameraRetryAfterError = std::chrono::seconds(2);

}  // namespace

void DeviceLink::apply_settings(const DeviceLinkInputs& in, gui::DeviceSettingsState& st) {
    if (in.session == nullptr || !in.attached || pending_settings_) return;
    for (const acquisition::DeviceSetting& s : st.edited.settings) {
        if (std::string problem = gui::setting_problem(s); !problem.empty()) {
            st.message = "Not applied: " + problem;
            st.message_is_error = true;
            return;
        }
    }
    pending_settings_ = in.session->apply_device_settings(st.edited);
    settings_applying_ = true;
    st.busy = true;
}

void DeviceLink::poll(const DeviceLinkInputs& in, gui::DevicePanelState& device) {
    if (in.attached && !device.connected && in.session != nullptr) {
        device.connected = true;  // attached (by "Connect" or the first capture): read it
        pending_settings_ = in.session->device_settings();
        device.settings.busy = true;
        cameras_wanted_ = cameras_due_ = true;
    }
    if (ready(pending_settings_)) take_settings(device);
    if (captures_seen_ != in.captures_finished) {  // a capture ended: a fresh view is due
        captures_seen_ = in.captures_finished;
        cameras_due_ = true;
        next_camera_grab_ = std::chrono::steady_clock::now() + kCameraGrabAfterCapture;
    }
    poll_cameras(in, device);
}

void DeviceLink::take_settings(gui::DevicePanelState& device) {
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
void DeviceLink::poll_cameras(const DeviceLinkInputs& in, gui::DevicePanelState& device) {
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
    if (!cameras_wanted_ || in.session == nullptr || !in.attached || in.capturing ||
        pending_cameras_ || pending_settings_ || now < next_camera_grab_)
        return;
    pending_cameras_ = in.session->preview_cameras(kCameraPreviewWidthPx);
}

}  // namespace anascan::field
