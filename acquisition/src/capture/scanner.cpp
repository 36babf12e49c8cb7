// The scanner thread of a capture session: opens the device, runs the operator's step,
// captures, and hands the scan to the persistence thread.
#include <algorithm>

#include "capture/impl.hpp"

namespace anascan::acquisition {
namespace {

std::size_t count_finite_points(const PointCloud& cloud) {
    return static_cast<std::size_t>(
        std::count_if(cloud.positions.begin(), cloud.positions.end(),
                      [](const Eigen::Vector3f& p) { return p.allFinite(); }));
}

/// FNV-1a over the points' bytes: a real scan's noise never repeats bit for bit.
std::uint64_t points_digest(const PointCloud& cloud) {
    std::uint64_t h = 1469598103934665603ull;
    const auto* bytes = reinterpret_cast<const unsigned char*>(cloud.positions.data());
    for (std::size_t i = 0; i < cloud.positions.size() * sizeof(Eigen::Vector3f); ++i)
        h = (h ^ bytes[i]) * 1099511628211ull;
    return h;
}

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
        report_device_error(opened.error());
        return fail(opened.error());
    }
    scanner = std::move(*opened);
    last_scan_digest.reset();  // a frozen device repeats itself while open
    if (scanner_failed) {
        scanner_failed = false;
        record_device_event(*store, "device-back", scanner_uri, "opened again");
        emit({.kind = SessionEventKind::kDeviceBack,
              .device = scanner_uri,
              .message = scanner_uri + ": back, capturing again"});
    }
    return {};
}

void CaptureSession::Impl::report_device_error(const Error& error) {
    scanner_failed = true;
    record_device_event(*store, "device-error", scanner_uri, error.message);
    emit({.kind = SessionEventKind::kDeviceError, .device = scanner_uri, .message = error.message});
}

Expected<void> CaptureSession::Impl::check_delivered(const Scan& scan) {
    const std::size_t finite = count_finite_points(scan.cloud);
    if (finite == 0)
        return fail(ErrorCode::kFormat,
                    scanner_uri + ": the scan has no valid point (" +
                        std::to_string(scan.cloud.size()) +
                        " points, none finite); nothing saved. Check the scanner's view and "
                        "exposure, then capture again");
    const std::uint64_t digest = points_digest(scan.cloud);
    if (last_scan_digest == digest)
        return fail(ErrorCode::kFormat,
                    scanner_uri +
                        ": delivered exactly the points of the previous scan, as a "
                        "frozen device does; nothing saved. Unplug and reconnect the "
                        "scanner if it happens again");
    last_scan_digest = digest;
    return {};
}

Expected<CapturedScan> CaptureSession::Impl::capture_one(PendingCapture& pending,
                                                         std::stop_token stop) {
    if (auto ok = open_if_needed(); !ok) return fail(ok.error());
    std::optional<Pose> to_truth_frame;
    if (pending.request.before) to_truth_frame = pending.request.before(*scanner);
    const drivers::CaptureControl control{
        .stop = stop,
        .timeout = config.capture_timeout,
        .on_warning = [this](const std::string& m) {
            record_device_event(*store, "device-warning", scanner_uri, m);
            emit({.kind = SessionEventKind::kDeviceWarning, .device = scanner_uri, .message = m});
        }};
    auto scan = scanner->capture_scan(control);
    if (!scan) {
        report_device_error(scan.error());
        if (scan.error().code == ErrorCode::kDisconnected) {
            scanner->close();
            scanner.reset();  // opened again at the next capture
        }
        return fail(scan.error());
    }
    if (auto ok = check_delivered(*scan); !ok) {
        report_device_error(ok.error());
        return fail(ok.error());
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
