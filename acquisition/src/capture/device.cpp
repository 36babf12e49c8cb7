// The operator's device calls of a capture session (settings, camera preview): queued to
// the scanner thread like captures, so they never run during one.
#include "anascan/drivers/settings.hpp"
#include "capture/device_settings_form.hpp"
#include "capture/impl.hpp"

namespace anascan::acquisition {
namespace {

/// How long a preview grab may wait for the cameras.
constexpr std::chrono::milliseconds kPreviewTimeout{5000};

/// Queues `work` (run with the open scanner) to the scanner thread; the future has its
/// result, or the error that kept the scanner from opening.
/// (`SessionImpl` is CaptureSession::Impl, deduced: the name is private to the session.)
template <typename T, typename SessionImpl, typename Work>
std::future<Expected<T>> queue_device_task(SessionImpl& impl, Work work) {
    auto promise = std::make_shared<std::promise<Expected<T>>>();
    auto future = promise->get_future();
    if (!impl.scanner_thread.joinable()) {
        promise->set_value(
            fail(ErrorCode::kInvalidArgument, "capture session: no scanner attached"));
        return future;
    }
    auto pending = std::make_shared<PendingCapture>();
    pending->device_task = [promise, work = std::move(work)](Expected<drivers::Scanner*> scanner) {
        promise->set_value(scanner ? work(**scanner) : Expected<T>(fail(scanner.error())));
    };
    if (!impl.requests.push(pending))
        promise->set_value(fail(ErrorCode::kCancelled, "capture session: stopping"));
    return future;
}

}  // namespace

void CaptureSession::Impl::run_device_task(PendingCapture& pending) {
    if (auto ok = open_if_needed(); !ok) {
        pending.device_task(fail(ok.error()));
        return;
    }
    pending.device_task(scanner.get());
}

std::future<Expected<DeviceSettingsForm>> CaptureSession::device_settings() {
    return queue_device_task<DeviceSettingsForm>(
        *impl_, [](drivers::Scanner& scanner) -> Expected<DeviceSettingsForm> {
            return settings_form(scanner);
        });
}

std::future<Expected<DeviceSettingsForm>> CaptureSession::apply_device_settings(
    DeviceSettingsForm form) {
    Impl& self = *impl_;
    return queue_device_task<DeviceSettingsForm>(
        self,
        [&self, form = std::move(form)](drivers::Scanner& scanner) -> Expected<DeviceSettingsForm> {
            auto requested = form_settings(form, scanner.capabilities());
            if (!requested) return fail(requested.error());
            if (auto ok = scanner.configure(*requested); !ok) return fail(ok.error());
            self.applied_settings = drivers::merge_settings(
                self.applied_settings.value_or(drivers::DeviceSettings{}), *requested);
            DeviceSettingsForm now = settings_form(scanner);
            // The event table is a log: failing to write it must not undo the settings.
            (void)self.store->add_event("device-settings", self.scanner_uri,
                                        settings_form_json(now));
            return now;
        });
}

std::future<Expected<CameraPreview>> CaptureSession::preview_cameras(int max_width_px) {
    return queue_device_task<CameraPreview>(
        *impl_, [max_width_px](drivers::Scanner& scanner) -> Expected<CameraPreview> {
            auto frames = scanner.preview_frames(kPreviewTimeout);
            if (!frames) return fail(frames.error());
            return camera_preview(scanner.info(), *frames, max_width_px);
        });
}

}  // namespace anascan::acquisition
