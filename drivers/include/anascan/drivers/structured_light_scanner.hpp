#pragma once
/// \file
/// The structured-light scanner as a device composed of a pattern output (projector) and
/// two cameras with their stereo calibration: capture_scan shows each pattern, takes from
/// each camera the first frame exposed after the pattern was on the output (older, stale
/// frames are dropped), then decodes and triangulates (structured_light/stereo_decoder.hpp)
/// into a Scan with per-point quality. The same class composes the real parts (GLFW
/// window, V4L2 cameras; `sl:` URIs, make_structured_light_backend) and the simulated
/// ones of sim/ (sim:structured-light).

#include <chrono>
#include <memory>
#include <string>

#include "anascan/drivers/camera.hpp"
#include "anascan/drivers/device_registry.hpp"
#include "anascan/drivers/pattern_output.hpp"
#include "anascan/drivers/scanner.hpp"
#include "anascan/drivers/structured_light/stereo_decoder.hpp"

namespace anascan::drivers {

/// What the scanner is made of. The cameras must deliver grey8, YUYV or MJPEG frames of
/// the calibration's image sizes; the output must have the pattern sequence's size.
struct StructuredLightParts {
    DeviceInfo info;  ///< uri and model; kind, is_scanner are set by the scanner.
    std::unique_ptr<PatternOutput> projector;
    std::unique_ptr<Camera> cam1;  ///< The calibration's cam1 (reconstruction frame).
    std::unique_ptr<Camera> cam2;
    sl::StereoCalibration calibration;
    sl::StereoDecodeConfig decode;  ///< sequence (pattern layout) and validity rules.
    /// Working range along cam1's axis, metres: the range_m capability.
    NumericRange range_m{0.3, 5.0};
    /// How much later than the start of its exposure a camera stamps a frame (0 for
    /// start-of-exposure stamps; about one frame period for stamps taken on arrival).
    std::chrono::nanoseconds frame_latency{0};
    /// Longest wait for one camera frame after a pattern (also bounded by the capture's).
    std::chrono::milliseconds frame_timeout{2000};
};

/// What the last capture saw (for tests and logs).
struct StructuredLightCaptureStats {
    std::size_t patterns_shown = 0;
    std::size_t frames_used = 0;        ///< Two per pattern when the capture completed.
    std::size_t stale_frames = 0;       ///< Dropped: exposed before their pattern was shown.
    std::size_t unreadable_frames = 0;  ///< Dropped: not a readable image (camera garbage).
    std::string last_unreadable;        ///< The last of those, naming its camera.
};

/// Not thread-safe (see Scanner). Owns its parts; close() closes both cameras.
class StructuredLightScanner final : public Scanner {
public:
    /// Checks the parts (present, sizes agree with the calibration and the sequence):
    /// kInvalidArgument naming the part otherwise.
    static Expected<std::unique_ptr<StructuredLightScanner>> create(StructuredLightParts parts);

    const DeviceInfo& info() const override { return parts_.info; }
    const Capabilities& capabilities() const override { return caps_; }
    /// exposure_us (the cameras', when they have it) and min/max_range_m.
    DeviceSettings settings() const override;
    /// exposure_us goes to both cameras; min/max_range_m bound the triangulated depths.
    Expected<void> configure(const DeviceSettings& requested) override;
    std::string calibration_json() const override;
    void close() override;
    /// Patterns → frames → decode. kTimeout when a camera stays silent (naming it),
    /// kDisconnected when a camera or the projector goes away (the scanner stays gone),
    /// kCancelled on a stop request; both streams are stopped on every path.
    Expected<Scan> capture_scan(const CaptureControl& control) override;
    /// Shows the all-white pattern and takes each camera's first frame exposed after it
    /// (structured_light_preview.cpp); both streams stopped on every path.
    Expected<std::vector<Frame>> preview_frames(std::chrono::milliseconds timeout) override;

    const StructuredLightCaptureStats& last_capture() const { return stats_; }
    const StructuredLightParts& parts() const { return parts_; }
    /// The parts, for the simulated twin that moves its cameras between captures.
    Camera& cam1() { return *parts_.cam1; }
    Camera& cam2() { return *parts_.cam2; }
    PatternOutput& projector() { return *parts_.projector; }

private:
    explicit StructuredLightScanner(StructuredLightParts parts);
    Expected<void> acquire(const CaptureControl& control, std::vector<cv::Mat>& images1,
                           std::vector<cv::Mat>& images2);
    Expected<Scan> decode(std::vector<cv::Mat>& images1, std::vector<cv::Mat>& images2);
    Error gone(const Error& error);

    StructuredLightParts parts_;
    Capabilities caps_;
    std::vector<Pattern> patterns_;
    double min_range_m_ = 0.0;
    double max_range_m_ = 0.0;
    StructuredLightCaptureStats stats_;
    std::int64_t sequence_ = 0;
    bool closed_ = false;
    bool disconnected_ = false;
};

/// The `sl:` backend: `sl:CALIBRATION.yml?cam1=URI&cam2=URI[&projector=N][&phase_steps=N]
/// [&phase_period_px=P][&latency_ms=T][&swap_cameras=1]`, the cameras opened by `cameras`
/// (v4l2:, usb:, playback:), the projector full-screen on monitor N (default: the last).
/// Not enumerable (a composition the user names).
Backend make_structured_light_backend(std::shared_ptr<const DeviceRegistry> cameras);

}  // namespace anascan::drivers
