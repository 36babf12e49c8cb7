// The scanner thread of a capture session: opens the device, runs the operator's step,
// captures, and hands the scan to the persistence thread.
#include "capture/impl.hpp"

namespace anascan::acquisition {
namespace {

void record_device_event(SessionStore& store, std::string_view kind, std::string_view uri,
                         std::string_view message) {
    // The event table is a log: failing to write it must not hide the device error itself.
    (void)store.add_event(kind, uri, message);
}

}  // namespace

void CaptureSession::Impl::scanner_loop(std::stop_token stop) {
    while (auto pending = requests.pop()) {
        if ((*pending)->device_task) {
            run_device_task(**pending);
            continue;
        }
        auto captured = capture_one(**pending, stop);
        if (!captured) {
            (*pending)->acknowledged.set_value(fail(captured.error()));
            end_work();
            continue;
        }
        auto item = std::make_shared<CapturedScan>(std::move(*captured));
        item->acknowledged = std::move((*pending)->acknowledged);
        if (!to_save.push(item)) {
            item->acknowledged.set_value(
                fail(ErrorCode::kCancelled, scanner_uri + ": session stopped before saving"));
            end_work();
        }
    }
    if (scanner) scanner->close();
}

Expected<void> CaptureSession::Impl::open_if_needed() {
    if (scanner) return {};
    auto opened = open_scanner();
    if (opened && applied_settings) {
        if (auto ok = (*opened)->configure(*applied_settings); !ok) opened = fail(ok.error());
    }
    if (!opened) {
        scanner_failed = true;
        record_device_event(*store, "device-error", scanner_uri, opened.error().message);
        emit({.kind = SessionEventKind::kDeviceError,
              .device = scanner_uri,
              .message = opened.error().message});
        return fail(opened.error());
    }
    scanner = std::move(*opened);
    if (scanner_failed) {
        scanner_failed = false;
        record_device_event(*store, "device-back", scanner_uri, "opened again");
        emit({.kind = SessionEventKind::kDeviceBack,
              .device = scanner_uri,
              .message = scanner_uri + ": back, capturing again"});
    }
    return {};
}

Expected<CapturedScan> CaptureSession::Impl::capture_one(PendingCapture& pending,
                                                         std::stop_token stop) {
    if (auto ok = open_if_needed(); !ok) return fail(ok.error());
    std::optional<Pose> to_truth_frame;
    if (pending.request.before) to_truth_frame = pending.request.before(*scanner);
    const drivers::CaptureControl control{.stop = stop, .timeout = config.capture_timeout};
    auto scan = scanner->capture_scan(control);
    if (!scan) {
        scanner_failed = true;
        record_device_event(*store, "device-error", scanner_uri, scan.error().message);
        emit({.kind = SessionEventKind::kDeviceError,
              .device = scanner_uri,
              .message = scan.error().message});
        if (scan.error().code == ErrorCode::kDisconnected) {
            scanner->close();
            scanner.reset();  // opened again at the next capture
        }
        return fail(scan.error());
    }
    CapturedScan captured;
    captured.scan = std::move(*scan);
    captured.turned_over = pending.request.turned_over;
    if (to_truth_frame && captured.scan.meta.T_world_scan) {
        captured.true_pose = *to_truth_frame * *captured.scan.meta.T_world_scan;
        captured.scan.meta.T_world_scan.reset();  // truth, not a prior for registration
    }
    return captured;
}

}  // namespace anascan::acquisition
