#pragma once
/// \file
/// Frame-time summary for the --frames report.

#include <time.h>

#include <algorithm>
#include <cmath>
#include <vector>

namespace anascan::field {

struct FrameTimeSummary {
    double median_ms = 0.0;
    double p95_ms = 0.0;
    double max_ms = 0.0;
};

/// Nearest-rank median and 95th percentile of the frame times (ms).
inline FrameTimeSummary summarize_frame_times(std::vector<double> ms) {
    if (ms.empty()) return {};
    std::sort(ms.begin(), ms.end());
    auto rank = [&](double q) {
        const auto i = static_cast<std::size_t>(std::ceil(q * static_cast<double>(ms.size())));
        return ms[std::clamp<std::size_t>(i, 1, ms.size()) - 1];
    };
    return {.median_ms = rank(0.5), .p95_ms = rank(0.95), .max_ms = ms.back()};
}

/// CPU time of the calling thread, ms.
inline double thread_cpu_ms() {
    timespec ts{};
    clock_gettime(CLOCK_THREAD_CPUTIME_ID, &ts);
    return static_cast<double>(ts.tv_sec) * 1e3 + static_cast<double>(ts.tv_nsec) / 1e6;
}

/// Where the time of the slow frames went: the parts of the frame (session poll; panels,
/// scene and ImGui's draw; the swap) and how much of it the UI thread ran on a CPU.
struct SlowFrames {
    double threshold_ms = 100.0;
    int count = 0;
    double wall_ms = 0.0, poll_ms = 0.0, draw_ms = 0.0, swap_ms = 0.0, cpu_ms = 0.0;
    void add(double wall, double poll, double draw, double swap, double cpu) {
        if (wall < threshold_ms) return;
        ++count;
        wall_ms += wall;
        poll_ms += poll;
        draw_ms += draw;
        swap_ms += swap;
        cpu_ms += cpu;
    }
};

}  // namespace anascan::field
