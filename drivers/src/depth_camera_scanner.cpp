#include "anascan/drivers/depth_camera_scanner.hpp"

#include <algorithm>
#include <chrono>

namespace anascan::drivers {
namespace {

/// Not thread-safe (see Scanner).
class DepthCameraScanner final : public Scanner {
public:
    DepthCameraScanner(std::unique_ptr<Camera> camera, const DepthIntrinsics& k)
        : camera_(std::move(camera)),
          intrinsics_(k),
          info_(camera_->info()),
          caps_(camera_->capabilities()) {
        info_.kind = DeviceKind::kTimeOfFlight;
        info_.is_scanner = true;
        info_.is_camera = false;
        caps_.can_capture_scan = true;
        caps_.can_stream = false;
    }
    const DeviceInfo& info() const override { return info_; }
    const Capabilities& capabilities() const override { return caps_; }
    DeviceSettings settings() const override { return camera_->settings(); }
    Expected<void> configure(const DeviceSettings& s) override { return camera_->configure(s); }
    std::string calibration_json() const override {
        return "{\"fx_px\":" + std::to_string(intrinsics_.fx_px) +
               ",\"fy_px\":" + std::to_string(intrinsics_.fy_px) +
               ",\"cx_px\":" + std::to_string(intrinsics_.cx_px) +
               ",\"cy_px\":" + std::to_string(intrinsics_.cy_px) +
               ",\"depth_unit_m\":" + std::to_string(intrinsics_.depth_unit_m) + "}";
    }
    void close() override { camera_->close(); }
    Expected<Scan> capture_scan(const CaptureControl& control) override;

private:
    Expected<Frame> wait_for_frame(const CaptureControl& control);
    std::unique_ptr<Camera> camera_;
    DepthIntrinsics intrinsics_;
    DeviceInfo info_;
    Capabilities caps_;
    std::int64_t sequence_ = 0;
};

// Waits in slices so that a stop request ends the wait within one slice.
Expected<Frame> DepthCameraScanner::wait_for_frame(const CaptureControl& control) {
    using std::chrono::milliseconds;
    const auto deadline = std::chrono::steady_clock::now() + control.timeout;
    for (;;) {
        if (control.stop.stop_requested())
            return fail(ErrorCode::kCancelled, info_.uri + ": cancelled");
        const auto left =
            std::chrono::duration_cast<milliseconds>(deadline - std::chrono::steady_clock::now());
        Expected<Frame> frame =
            camera_->next_frame(std::clamp(left, milliseconds(1), milliseconds(100)));
        if (frame || frame.error().code != ErrorCode::kTimeout) return frame;
        if (std::chrono::steady_clock::now() >= deadline) {
            return fail(ErrorCode::kTimeout, info_.uri + ": no depth frame within " +
                                                 std::to_string(control.timeout.count()) + " ms");
        }
    }
}

Expected<Scan> DepthCameraScanner::capture_scan(const CaptureControl& control) {
    if (control.stop.stop_requested())
        return fail(ErrorCode::kCancelled, info_.uri + ": cancelled");
    if (control.on_progress) control.on_progress({0.0, "waiting for a depth frame"});
    if (auto ok = camera_->start_stream(); !ok) return fail(ok.error());
    Expected<Frame> frame = wait_for_frame(control);
    camera_->stop_stream();
    if (!frame) return fail(frame.error());
    auto cloud = depth_to_point_cloud(*frame, intrinsics_);
    if (!cloud) return fail(Error{cloud.error().code, info_.uri + ": " + cloud.error().message});
    Scan scan;
    scan.cloud = std::move(*cloud);
    scan.meta.id = "depth-" + std::to_string(sequence_);
    scan.meta.sequence = sequence_++;
    scan.meta.device_id = info_.uri;
    scan.meta.device_kind = DeviceKind::kTimeOfFlight;
    scan.meta.sensor_origin_scan_m = Eigen::Vector3d::Zero();
    scan.meta.time = std::chrono::system_clock::now();
    scan.meta.settings_json = settings_to_json(settings());
    if (control.on_progress) control.on_progress({1.0, "depth frame converted"});
    return scan;
}

}  // namespace

std::unique_ptr<Scanner> make_depth_camera_scanner(std::unique_ptr<Camera> camera,
                                                   const DepthIntrinsics& intrinsics) {
    return std::make_unique<DepthCameraScanner>(std::move(camera), intrinsics);
}

}  // namespace anascan::drivers
