#include "anascan/drivers/depth_camera_scanner.hpp"

#include <algorithm>
#include <chrono>
#include <optional>
#include <string>

#include "uri_query.hpp"

namespace anascan::drivers {
namespace {

/// Not thread-safe (see Scanner).
class DepthCameraScanner final : public Scanner {
public:
    DepthCameraScanner(std::unique_ptr<Camera> camera, const DepthIntrinsics& k,
                       std::string uri = {})
        : camera_(std::move(camera)),
          intrinsics_(k),
          info_(camera_->info()),
          caps_(camera_->capabilities()) {
        if (!uri.empty()) info_.uri = std::move(uri);
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

// Waits in slices so that a stop request ends the wait within one slice. An unreadable
// frame (kFormat: short, bad header) is dropped and the next one awaited.
Expected<Frame> DepthCameraScanner::wait_for_frame(const CaptureControl& control) {
    using std::chrono::milliseconds;
    const auto deadline = std::chrono::steady_clock::now() + control.timeout;
    std::optional<Error> unreadable;
    int dropped = 0;
    for (;;) {
        if (control.stop.stop_requested())
            return fail(ErrorCode::kCancelled, info_.uri + ": cancelled");
        const auto left =
            std::chrono::duration_cast<milliseconds>(deadline - std::chrono::steady_clock::now());
        Expected<Frame> frame =
            camera_->next_frame(std::clamp(left, milliseconds(1), milliseconds(100)));
        if (!frame && frame.error().code == ErrorCode::kFormat) {
            unreadable = frame.error();
            ++dropped;
        } else if (frame || frame.error().code != ErrorCode::kTimeout) {
            return frame;
        }
        if (std::chrono::steady_clock::now() < deadline) continue;
        const std::string within = std::to_string(control.timeout.count()) + " ms";
        if (!unreadable)
            return fail(ErrorCode::kTimeout, info_.uri + ": no depth frame within " + within);
        return fail(ErrorCode::kFormat, info_.uri + ": no readable depth frame within " + within +
                                            " (" + std::to_string(dropped) +
                                            " unreadable; the last: " + unreadable->message + ")");
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

namespace {

Expected<std::unique_ptr<Device>> open_depth_scanner(const DeviceRegistry& cameras,
                                                     const DeviceUri& uri) {
    const std::string text = to_string(uri);
    auto q =
        parse_uri_query(text, uri.target, {"fx_px", "fy_px", "cx_px", "cy_px", "depth_unit_m"});
    if (!q) return fail(q.error());
    DepthIntrinsics k;
    for (auto [key, out] : {std::pair{"fx_px", &k.fx_px}, std::pair{"fy_px", &k.fy_px},
                            std::pair{"cx_px", &k.cx_px}, std::pair{"cy_px", &k.cy_px}}) {
        if (!q->values.contains(key))
            return fail(
                ErrorCode::kInvalidArgument,
                text + ": missing " + key + " (depth:CAMERA_URI?fx_px=F&fy_px=F&cx_px=C&cy_px=C)");
        auto v = query_double(*q, key, 0.0, text);
        if (!v) return fail(v.error());
        *out = *v;
    }
    auto unit = query_double(*q, "depth_unit_m", k.depth_unit_m, text);
    if (!unit) return fail(unit.error());
    k.depth_unit_m = *unit;
    if (!(k.fx_px > 0.0) || !(k.fy_px > 0.0) || !(k.depth_unit_m > 0.0))
        return fail(ErrorCode::kInvalidArgument,
                    text + ": fx_px, fy_px and depth_unit_m must be positive");
    auto camera = open_as_camera(cameras, q->path);
    if (!camera) return fail(camera.error().code, text + ": " + camera.error().message);
    return std::unique_ptr<Device>(
        std::make_unique<DepthCameraScanner>(std::move(*camera), k, text));
}

}  // namespace

Backend make_depth_scanner_backend(std::shared_ptr<const DeviceRegistry> cameras) {
    return Backend{
        .scheme = "depth",
        .description =
            "depth camera as a scanner: "
            "depth:v4l2:/dev/video2?fx_px=F&fy_px=F&cx_px=C&cy_px=C"
            "[&depth_unit_m=0.001]",
        .enumerate = [] { return std::vector<DeviceInfo>{}; },
        .open = [cameras](const DeviceUri& uri) { return open_depth_scanner(*cameras, uri); }};
}

}  // namespace anascan::drivers
