#pragma once
/// \file
/// Frame-time measurement of a headless run: each frame's wall time and its parts (session
/// poll; panels, scene and ImGui's draw; the swap), reported on stderr at the end: all
/// counted frames, those that drew points, frames while capturing or registering, frames
/// that uploaded points, and where the time of the slow frames went.

#include <chrono>
#include <cstddef>
#include <string>
#include <vector>

#include "anascan/gui/point_renderer.hpp"
#include "frame_times.hpp"

namespace anascan::field {

struct FrameMeterConfig {
    double slow_frame_ms = 100.0;  ///< Frames this long are broken down into their parts.
};

/// What the loop knew about one frame when it ended.
struct FrameFacts {
    bool counted = false;      ///< Counted toward the headless run's frames.
    bool busy = false;         ///< A capture or registrations were pending.
    bool uploaded = false;     ///< Points were copied to the GPU.
    bool drew_points = false;  ///< Not only a copy of a complete image.
};

/// What the report names besides the frame times.
struct FrameReportInputs {
    gui::DrawStats last;                 ///< The last frame's draw.
    std::size_t budget_points = 0;       ///< The LOD budget at the end.
    std::string renderer_name;           ///< GL renderer.
    std::size_t points_total = 0;        ///< In the view at the end.
    std::vector<double> upload_work_ms;  ///< The uploads' own work (SessionLink).
};

class FrameMeter {
public:
    explicit FrameMeter(FrameMeterConfig config = {})
        : slow_{.threshold_ms = config.slow_frame_ms} {}

    /// The frame starts (after the wait for input: the time to react and draw).
    void begin();
    void polled() { polled_ = now(); }
    void drawn() { drawn_ = now(); }
    /// After the swap.
    void end(const FrameFacts& facts);
    /// Wall time of the frame that ended last, ms.
    double last_ms() const { return last_ms_; }
    /// Frames ended so far.
    int frames() const { return frames_; }
    /// The report on stderr.
    void report(const FrameReportInputs& inputs) const;

private:
    using Clock = std::chrono::steady_clock;
    static Clock::time_point now() { return Clock::now(); }

    Clock::time_point start_, polled_, drawn_;
    double cpu_start_ms_ = 0.0;
    double last_ms_ = 0.0;
    int frames_ = 0;
    SlowFrames slow_;
    std::vector<double> counted_ms_, busy_ms_, upload_ms_;
    std::vector<bool> drew_;
};

}  // namespace anascan::field
