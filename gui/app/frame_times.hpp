#pragma once
/// \file
/// Frame-time summary for the --frames report.

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

}  // namespace anascan::field
