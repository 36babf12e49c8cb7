// The campaign's prepare stage: register's preparation and the summary of a scan.
#include <string>

#include "anascan/processing/campaign/campaign_stages.hpp"
#include "anascan/processing/features/integral_invariants.hpp"
#include "registration/batch/steps.hpp"

namespace anascan {

PreparedSummary prepare_campaign_scan(PointCloud& cloud, const CampaignConfig& config) {
    PreparedSummary out;
    const std::size_t loaded = cloud.size();
    out.normals_estimated = !cloud.has_normals();
    out.points = prepare_scan(cloud, std::nullopt, config.registration);
    if (out.points < config.min_scan_points) {
        out.problem = loaded == 0 ? "empty scan (no points)"
                                  : "only " + std::to_string(out.points) + " usable points of " +
                                        std::to_string(loaded) + " (at least " +
                                        std::to_string(config.min_scan_points) + " are needed)";
        return out;
    }
    const detail::ScanSummary summary = detail::summarize(cloud);
    out.spacing_m = median_sample_spacing_m(cloud);
    out.centre_m = summary.centre_m;
    out.diagonal_m = summary.diagonal_m;
    out.position_hash = summary.position_hash;
    if (!(out.diagonal_m > 0.0) || !(out.spacing_m > 0.0)) {
        out.problem = "the prepared points have no extent (all at one position)";
    }
    return out;
}

}  // namespace anascan
