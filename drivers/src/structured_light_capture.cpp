// StructuredLightScanner::capture_scan: show each pattern, take each camera's first frame
// exposed after it, decode.
#include <tbb/parallel_invoke.h>

#include <algorithm>

#include "anascan/drivers/structured_light_scanner.hpp"
#include "frame_grey.hpp"

namespace anascan::drivers {
namespace {

using std::chrono::milliseconds;
using std::chrono::steady_clock;

/// A stop request ends a wait for a frame within one slice.
constexpr milliseconds kWaitSlice{100};

std::string part_name(const char* label, const Camera& camera) {
    return std::string(label) + " (" + camera.info().uri + ")";
}

/// Stops both streams on every path out of a capture.
class Streams {
public:
    Streams(Camera& a, Camera& b) : a_(a), b_(b) {}
    ~Streams() {
        if (a_on_) a_.stop_stream();
        if (b_on_) b_.stop_stream();
    }
    Streams(const Streams&) = delete;
    Streams& operator=(const Streams&) = delete;
    Expected<void> start(const char* la, const char* lb) {
        if (auto ok = a_.start_stream(); !ok)
            return fail(ok.error().code, part_name(la, a_) + ": " + ok.error().message);
        a_on_ = true;
        if (auto ok = b_.start_stream(); !ok)
            return fail(ok.error().code, part_name(lb, b_) + ": " + ok.error().message);
        b_on_ = true;
        return {};
    }

private:
    Camera& a_;
    Camera& b_;
    bool a_on_ = false;
    bool b_on_ = false;
};

/// One pattern's wait for the frames of the cameras.
struct FrameWait {
    const CaptureControl& control;
    steady_clock::time_point deadline;  ///< Of the whole capture.
    std::chrono::nanoseconds shown_at;  ///< Of the pattern.
    std::chrono::nanoseconds latency;   ///< Frame stamp minus start of its exposure.
    milliseconds frame_timeout;
    std::string what;  ///< "pattern 3/46"
};

std::string ms_text(std::chrono::nanoseconds t) {
    return std::to_string(std::chrono::duration_cast<milliseconds>(t).count()) + " ms";
}

/// The first frame of `camera` exposed after the pattern was shown; older frames are
/// counted in `stale` and dropped, unreadable ones (kFormat) dropped and named on a timeout.
/// What one camera's frames of one pattern held besides the one used.
struct FrameTally {
    std::size_t stale = 0, unreadable = 0;
    std::string last_unreadable;
};

Expected<cv::Mat> fresh_frame(Camera& camera, const char* label, const FrameWait& w,
                              FrameTally& tally) {
    const auto frame_deadline = std::min(w.deadline, steady_clock::now() + w.frame_timeout);
    std::string unreadable;
    for (;;) {
        if (w.control.stop.stop_requested())
            return fail(ErrorCode::kCancelled, "capture cancelled at " + w.what);
        const auto now = steady_clock::now();
        if (now >= frame_deadline) {
            const bool whole = frame_deadline == w.deadline;
            return fail(ErrorCode::kTimeout,
                        part_name(label, camera) + " delivered no frame of " + w.what + " within " +
                            ms_text(whole ? w.control.timeout : w.frame_timeout) +
                            (whole ? " (the capture's timeout)" : "") +
                            (unreadable.empty() ? "" : "; the last was unreadable: " + unreadable));
        }
        const auto left = std::chrono::duration_cast<milliseconds>(frame_deadline - now);
        Expected<Frame> frame = camera.next_frame(std::clamp(left, milliseconds(1), kWaitSlice));
        if (!frame) {
            if (frame.error().code == ErrorCode::kTimeout) continue;
            if (frame.error().code == ErrorCode::kFormat) {
                unreadable = frame.error().message;
                ++tally.unreadable;
                tally.last_unreadable = part_name(label, camera) + ": " + unreadable;
                continue;
            }
            return fail(frame.error().code,
                        part_name(label, camera) + " at " + w.what + ": " + frame.error().message);
        }
        if (frame->timestamp_ns - w.latency < w.shown_at) {
            ++tally.stale;
            continue;
        }
        return frame_to_grey(*frame, part_name(label, camera));
    }
}

void report(const CaptureControl& control, double fraction, std::string stage) {
    if (control.on_progress) control.on_progress({fraction, std::move(stage)});
}

}  // namespace

Expected<void> StructuredLightScanner::acquire(const CaptureControl& control,
                                               std::vector<cv::Mat>& images1,
                                               std::vector<cv::Mat>& images2) {
    const auto deadline = steady_clock::now() + control.timeout;
    Streams streams(*parts_.cam1, *parts_.cam2);
    if (auto ok = streams.start("cam1", "cam2"); !ok) return fail(gone(ok.error()));
    const std::size_t n = patterns_.size();
    for (std::size_t i = 0; i < n; ++i) {
        const std::string what = "pattern " + std::to_string(i + 1) + "/" + std::to_string(n);
        if (control.stop.stop_requested())
            return fail(gone({ErrorCode::kCancelled, "capture cancelled before " + what}));
        if (steady_clock::now() >= deadline)
            return fail(gone({ErrorCode::kTimeout, "no scan within " + ms_text(control.timeout) +
                                                       " (at " + what + ")"}));
        report(control, 0.9 * static_cast<double>(i) / static_cast<double>(n),
               "projecting " + what);
        auto shown = parts_.projector->show(i);
        if (!shown)
            return fail(gone({shown.error().code, parts_.projector->name() + " at " + what + ": " +
                                                      shown.error().message}));
        ++stats_.patterns_shown;
        const FrameWait wait{control, deadline, *shown, parts_.frame_latency, parts_.frame_timeout,
                             what};
        // Both cameras at once (each on one thread, as Camera requires).
        FrameTally tally1, tally2;
        Expected<cv::Mat> a = cv::Mat(), b = cv::Mat();
        tbb::parallel_invoke([&] { a = fresh_frame(*parts_.cam1, "cam1", wait, tally1); },
                             [&] { b = fresh_frame(*parts_.cam2, "cam2", wait, tally2); });
        for (const FrameTally& t : {tally1, tally2}) {
            stats_.stale_frames += t.stale;
            stats_.unreadable_frames += t.unreadable;
            if (!t.last_unreadable.empty()) stats_.last_unreadable = t.last_unreadable;
        }
        if (!a) return fail(gone(a.error()));
        if (!b) return fail(gone(b.error()));
        images1.push_back(std::move(*a));
        images2.push_back(std::move(*b));
        stats_.frames_used += 2;
    }
    return {};
}

Expected<Scan> StructuredLightScanner::capture_scan(const CaptureControl& control) {
    if (closed_) return fail(ErrorCode::kDisconnected, parts_.info.uri + ": closed");
    if (disconnected_)
        return fail(ErrorCode::kDisconnected, parts_.info.uri + ": a part went away");
    stats_ = {};
    std::vector<cv::Mat> images1, images2;
    if (auto ok = acquire(control, images1, images2); !ok) return fail(ok.error());
    if (stats_.unreadable_frames > 0 && control.on_warning) {
        control.on_warning(parts_.info.uri + ": " + std::to_string(stats_.unreadable_frames) +
                           " unreadable camera frame(s) dropped; the scan is made of good ones "
                           "(the last: " +
                           stats_.last_unreadable + ")");
    }
    if (control.stop.stop_requested())
        return fail(ErrorCode::kCancelled, parts_.info.uri + ": capture cancelled");
    report(control, 0.9, "decoding");
    auto scan = decode(images1, images2);
    if (scan) report(control, 1.0, "scan complete");
    return scan;
}

Expected<Scan> StructuredLightScanner::decode(std::vector<cv::Mat>& images1,
                                              std::vector<cv::Mat>& images2) {
    sl::StereoDecodeConfig config = parts_.decode;
    config.triangulation.min_depth_m = min_range_m_;
    config.triangulation.max_depth_m = max_range_m_;
    auto decoded = sl::decode_stereo(images1, images2, parts_.calibration, config);
    if (!decoded)
        return fail(decoded.error().code, parts_.info.uri + ": " + decoded.error().message);
    Scan scan;
    scan.cloud = std::move(decoded->cloud);
    scan.meta.id = "sl-" + std::to_string(sequence_);
    scan.meta.sequence = sequence_++;
    scan.meta.device_id = parts_.info.uri;
    scan.meta.device_kind = DeviceKind::kStructuredLight;
    scan.meta.sensor_origin_scan_m = Eigen::Vector3d::Zero();
    scan.meta.time = std::chrono::system_clock::now();
    scan.meta.settings_json = settings_to_json(settings());
    return scan;
}

}  // namespace anascan::drivers

namespace anascan::drivers {

Expected<std::vector<Frame>> StructuredLightScanner::preview_frames(
    std::chrono::milliseconds timeout) {
    if (closed_) return fail(ErrorCode::kDisconnected, parts_.info.uri + ": closed");
    if (disconnected_)
        return fail(ErrorCode::kDisconnected, parts_.info.uri + ": a part went away");
    const CaptureControl control{.timeout = timeout};
    Streams streams(*parts_.cam1, *parts_.cam2);
    if (auto ok = streams.start("cam1", "cam2"); !ok) return fail(gone(ok.error()));
    const auto white = static_cast<std::size_t>(parts_.decode.sequence.gray.white_index());
    auto shown = parts_.projector->show(white);
    if (!shown)
        return fail(gone({shown.error().code,
                          parts_.projector->name() + " at the preview: " + shown.error().message}));
    const FrameWait wait{control, steady_clock::now() + timeout,
                         *shown,  parts_.frame_latency,
                         timeout, "the preview"};
    FrameTally tally1, tally2;  // The preview keeps no figures.
    Expected<cv::Mat> a = cv::Mat(), b = cv::Mat();
    tbb::parallel_invoke([&] { a = fresh_frame(*parts_.cam1, "cam1", wait, tally1); },
                         [&] { b = fresh_frame(*parts_.cam2, "cam2", wait, tally2); });
    if (!a) return fail(gone(a.error()));
    if (!b) return fail(gone(b.error()));
    std::vector<Frame> frames;
    for (const cv::Mat* image : {&*a, &*b}) {
        Frame frame{.width = image->cols,
                    .height = image->rows,
                    .format = PixelFormat::kGrey8,
                    .stride_bytes = static_cast<std::size_t>(image->cols),
                    .timestamp_ns = *shown};
        frame.data.resize(frame.stride_bytes * static_cast<std::size_t>(image->rows));
        for (int r = 0; r < image->rows; ++r)
            std::copy_n(image->ptr<std::uint8_t>(r), image->cols,
                        frame.data.data() + frame.stride_bytes * static_cast<std::size_t>(r));
        frames.push_back(std::move(frame));
    }
    return frames;
}

}  // namespace anascan::drivers
