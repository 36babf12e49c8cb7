#include "frame_meter.hpp"

#include <cstdio>

namespace anascan::field {
namespace {

using Ms = std::chrono::duration<double, std::milli>;

/// All counted frames, and those that drew points apart from the copies of a complete
/// image. The first counted frame compiles shaders and fills caches: it is left out.
void report_counted(const std::vector<double>& frame_ms, const std::vector<bool>& drew,
                    const FrameReportInputs& in) {
    std::vector<double> steady, drawing, copies;
    for (std::size_t i = 1; i < frame_ms.size(); ++i) {
        steady.push_back(frame_ms[i]);
        (drew[i] ? drawing : copies).push_back(frame_ms[i]);
    }
    const FrameTimeSummary s = summarize_frame_times(steady);
    const FrameTimeSummary d = summarize_frame_times(drawing);
    const FrameTimeSummary c = summarize_frame_times(copies);
    std::fprintf(stderr,
                 "anascan-field: %zu frames (first excluded): frame time median %.1f ms, "
                 "p95 %.1f ms, max %.1f ms\n"
                 "  %zu frames drew points: median %.1f ms, p95 %.1f ms; %zu copied the complete "
                 "image: median %.1f ms, p95 %.1f ms\n"
                 "  image holds %zu of %zu points (budget %zu points per frame); GL renderer %s\n",
                 steady.size(), s.median_ms, s.p95_ms, s.max_ms, drawing.size(), d.median_ms,
                 d.p95_ms, copies.size(), c.median_ms, c.p95_ms, in.last.points_in_image,
                 in.last.points_visible, in.budget_points, in.renderer_name.c_str());
}

/// Frame times while a capture or registrations were pending.
void report_busy(const std::vector<double>& busy_ms, std::size_t points) {
    if (busy_ms.empty()) return;
    const FrameTimeSummary b = summarize_frame_times(busy_ms);
    std::fprintf(stderr,
                 "anascan-field: %zu frames while capturing or registering: frame time median "
                 "%.1f ms, p95 %.1f ms, max %.1f ms (%zu points in the view at the end)\n",
                 busy_ms.size(), b.median_ms, b.p95_ms, b.max_ms, points);
}

/// Frames that copied a new scan's points to the GPU (all of a scan, or a step of it),
/// and the time the upload itself took in them (taking the scan, copying its points).
void report_uploads(const std::vector<double>& upload_ms, const std::vector<double>& work_ms) {
    if (upload_ms.empty()) return;
    const FrameTimeSummary u = summarize_frame_times(upload_ms);
    const FrameTimeSummary w = summarize_frame_times(work_ms);
    std::fprintf(stderr,
                 "anascan-field: %zu frames uploaded points: frame time median %.1f ms, p95 "
                 "%.1f ms, max %.1f ms; the upload's own work median %.2f ms, max %.2f ms\n",
                 upload_ms.size(), u.median_ms, u.p95_ms, u.max_ms, w.median_ms, w.max_ms);
}

/// Frames over the threshold: the mean of each part, and of the UI thread's CPU time.
void report_slow(const SlowFrames& slow) {
    if (slow.count == 0) return;
    const double n = slow.count;
    std::fprintf(stderr,
                 "anascan-field: %d frames over %.0f ms: mean %.0f ms = session poll %.1f + "
                 "panels, scene and ImGui draw %.1f + swap %.1f ms; the UI thread ran %.1f "
                 "ms of it on a CPU\n",
                 slow.count, slow.threshold_ms, slow.wall_ms / n, slow.poll_ms / n,
                 slow.draw_ms / n, slow.swap_ms / n, slow.cpu_ms / n);
}

}  // namespace

void FrameMeter::begin() {
    start_ = polled_ = drawn_ = now();
    cpu_start_ms_ = thread_cpu_ms();
}

void FrameMeter::end(const FrameFacts& facts) {
    const Clock::time_point end = now();
    last_ms_ = Ms(end - start_).count();
    const bool first = frames_++ == 0;  // compiles shaders: not a steady-state frame
    if (!first) {
        slow_.add(last_ms_, Ms(polled_ - start_).count(), Ms(drawn_ - polled_).count(),
                  Ms(end - drawn_).count(), thread_cpu_ms() - cpu_start_ms_);
    }
    if (facts.counted) {
        counted_ms_.push_back(last_ms_);
        drew_.push_back(facts.drew_points);
    }
    if (facts.busy && !first) busy_ms_.push_back(last_ms_);
    if (facts.uploaded) upload_ms_.push_back(last_ms_);
}

void FrameMeter::report(const FrameReportInputs& inputs) const {
    report_counted(counted_ms_, drew_, inputs);
    report_busy(busy_ms_, inputs.points_total);
    report_uploads(upload_ms_, inputs.upload_work_ms);
    report_slow(slow_);
}

}  // namespace anascan::field
