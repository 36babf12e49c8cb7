// The campaign's pairwise stage: one pair's global registration.
#include "anascan/processing/campaign/campaign_stages.hpp"
#include "anascan/processing/core/stopwatch.hpp"

namespace anascan {

CampaignPairResult register_campaign_pair(const PointCloud& source, const PointCloud& target,
                                          const CampaignConfig& config) {
    const Stopwatch watch;
    const GlobalRegistrationResult g = register_global(source, target, config.registration.global);
    CampaignPairResult out{.status = g.status,
                           .verified = g.status == GlobalRegistrationStatus::kSuccess,
                           .rms_m = g.rms_m,
                           .overlap_fraction = g.overlap_fraction,
                           .target_spacing_m = g.target_spacing_m,
                           .slide_ambiguous = g.slide_ambiguous};
    if (out.verified) out.T_target_source = g.T_target_source;
    out.time_s = watch.seconds();
    return out;
}

}  // namespace anascan
