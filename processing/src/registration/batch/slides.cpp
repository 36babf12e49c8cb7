// register_scans: the warning for placed scans whose links all ended still sliding.
#include <algorithm>
#include <cstdio>
#include <string>

#include "registration/batch/steps.hpp"

namespace anascan::detail {
namespace {

/// "(0.72, -0.50, 0.46)"
std::string direction_text(const Eigen::Vector3d& d) {
    char text[64];
    std::snprintf(text, sizeof text, "(%.2f, %.2f, %.2f)", d.x(), d.y(), d.z());
    return text;
}

std::string ratio_text(double ratio) {
    char text[32];
    std::snprintf(text, sizeof text, "%.4f", ratio);
    return text;
}

}  // namespace

void warn_sliding_scans(const ScanRegistrationConfig& config, ScanRegistrationResult& result) {
    const double limit = config.sliding_link_max_eigenvalue_ratio;
    if (limit <= 0.0) return;
    for (std::size_t i = 0; i < result.scans.size(); ++i) {
        ScanOutcome& scan = result.scans[i];
        if (!scan.placed) continue;
        std::size_t links = 0, sliding = 0;
        double worst_ratio = 1.0;
        Eigen::Vector3d direction_world = Eigen::Vector3d::Zero();
        for (const PairOutcome& p : result.pairs) {
            if ((p.source != i && p.target != i) || !p.linked || p.link_dropped) continue;
            ++links;
            if (p.fine.status != FineRegistrationStatus::kMaxIterations ||
                p.fine.eigenvalue_ratio >= limit)
                continue;
            ++sliding;
            if (p.fine.eigenvalue_ratio < worst_ratio) {
                worst_ratio = p.fine.eigenvalue_ratio;
                direction_world =
                    result.scans[p.target].T_world_scan.linear() * p.fine.weakest_translation;
            }
        }
        if (links == 0 || sliding < links) continue;
        const std::string text =
            "pose along " + direction_text(direction_world) +
            " (world frame) not fixed by its overlaps: its " + std::to_string(links) +
            (links == 1 ? " link" : " links") +
            " ended still sliding along a weak direction (eigenvalue ratio down to " +
            ratio_text(worst_ratio) + "); it may be off along it";
        scan.warning = scan.warning.empty() ? text : scan.warning + "; " + text;
    }
}

}  // namespace anascan::detail
