// The campaign's pairwise stage and match graph: one pair's global registration, and the
// stones as connected components of the verified pairs under the campaign RMS gate.
#include <algorithm>
#include <numeric>

#include "anascan/processing/campaign/campaign_stages.hpp"
#include "anascan/processing/core/stopwatch.hpp"
#include "registration/batch/steps.hpp"

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

StoneGraph find_stones(std::size_t scan_count, const std::vector<RegisteredPair>& pairs,
                       const CampaignConfig& config) {
    std::vector<PairOutcome> outcomes;
    for (const RegisteredPair& p : pairs) {
        PairOutcome o{.source = p.source, .target = p.target};
        o.verified = p.result.verified;
        o.global.rms_m = p.result.rms_m;
        o.global.target_spacing_m = p.result.target_spacing_m;
        outcomes.push_back(o);
    }
    StoneGraph out;
    out.rms_gate_m = detail::session_rms_gate_m(outcomes, scan_count, config.registration);
    detail::DisjointSets sets(scan_count);
    for (PairOutcome& o : outcomes) {
        out.gated_pairs += detail::apply_rms_gate(o, out.rms_gate_m);
        if (o.verified) sets.unite(o.source, o.target);
    }
    std::vector<std::vector<std::size_t>> members(scan_count);
    for (std::size_t i = 0; i < scan_count; ++i) members[sets.find(i)].push_back(i);
    for (std::vector<std::size_t>& m : members) {
        if (m.size() >= 2) out.stones.push_back(std::move(m));
    }
    std::stable_sort(out.stones.begin(), out.stones.end(),
                     [](const auto& a, const auto& b) { return a.size() > b.size(); });
    out.stone_of_scan.assign(scan_count, -1);
    for (std::size_t s = 0; s < out.stones.size(); ++s) {
        for (std::size_t i : out.stones[s]) out.stone_of_scan[i] = static_cast<int>(s);
    }
    return out;
}

}  // namespace anascan
