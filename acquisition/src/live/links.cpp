// LiveRegistrar: multi-view links between overlapping scans of a group, each scan linked to
// the earlier scans of each side it is predicted to overlap most.
#include <algorithm>
#include <map>
#include <utility>
#include <vector>

#include "anascan/processing/registration/multiview/link_compression.hpp"
#include "anascan/processing/spatial/kdtree.hpp"
#include "live/state.hpp"
#include "live/votes.hpp"

namespace anascan::acquisition {
namespace {

using live::ScanEntry;

/// Fraction of (about 200) source points that land within `distance_m` of the target under
/// `T_target_source`: a cheap forecast of a pair's overlap.
double forecast_overlap(const ScanEntry& source, const ScanEntry& target, const KdTree& tree,
                        const Pose& T_target_source, double distance_m) {
    const std::size_t step = std::max<std::size_t>(1, source.cloud.size() / 200);
    const Eigen::Isometry3f T_local =
        (Eigen::Translation3d(-target.cloud.origin_m) * T_target_source *
         Eigen::Translation3d(source.cloud.origin_m))
            .cast<float>();
    std::size_t near = 0, tried = 0;
    Neighbor nearest;
    for (std::size_t i = 0; i < source.cloud.size(); i += step, ++tried) {
        near += tree.nearest_within(T_local * source.cloud.positions[i],
                                    static_cast<float>(distance_m), nearest);
    }
    return tried == 0 ? 0.0 : static_cast<double>(near) / static_cast<double>(tried);
}

bool usable_link(const FineRegistrationResult& fine, const LiveRegistrationConfig& config) {
    // A degenerate link moved only along the directions its overlap fixes; fewer
    // iterations than the limit means it settled along those.
    const bool settled_on_what_it_fixes = config.links.degenerate &&
                                          fine.status == FineRegistrationStatus::kDegenerate &&
                                          fine.iterations < config.links.fine.max_iterations;
    return (fine.status == FineRegistrationStatus::kConverged ||
            fine.status == FineRegistrationStatus::kMaxIterations || settled_on_what_it_fixes) &&
           fine.overlap_fraction >= config.links.min_overlap_fraction &&
           fine.normal_deviation_deg.value_or(0.0) <= config.verify.max_normal_deviation_deg &&
           fine.rms_m <= config.links.max_rms_voxel_factor * config.prepare.voxel_size_m;
}

}  // namespace

const KdTree& LiveRegistrar::State::tree_of(std::size_t i) {
    std::shared_ptr<const KdTree>& tree = scans[i].tree;  // Kept: the cloud never changes.
    if (!tree) tree = std::make_shared<const KdTree>(scans[i].cloud.positions);
    return *tree;
}

double LiveRegistrar::State::forecast(std::size_t t, std::size_t s, const Pose& initial) {
    auto& [at, fraction] = link_forecasts[{t, s}];
    if (fraction < 0.0 || !live::poses_agree(at, initial, scans[s].centroid_m,
                                             config.links.retry_deg, config.links.retry_m)) {
        fraction = forecast_overlap(scans[s], scans[t], tree_of(t), initial,
                                    config.links.fine.overlap_distance_m);
        at = initial;
    }
    return fraction;
}

std::vector<std::size_t> LiveRegistrar::State::link_partners(std::size_t s) {
    std::vector<std::pair<double, std::size_t>> ranked;  // (forecast, t), t < s.
    for (std::size_t t = 0; t < s; ++t) {
        if (!live::active(scans[t]) || scans[s].group != scans[t].group) continue;
        const Pose initial = scans[t].T_group_scan.inverse() * scans[s].T_group_scan;
        const double fraction = forecast(t, s, initial);
        if (fraction >= config.links.min_overlap_fraction) ranked.emplace_back(fraction, t);
    }
    std::sort(ranked.begin(), ranked.end(), std::greater<>());
    // The cap holds per side of the partner: the few links across a turn-over overlap
    // little (a band of the sides) and would always lose to the scan's own side, yet they
    // are what holds the two sides together (without them the small block's second side
    // hung on the merge alone, 0.0063° off instead of 0.0035°).
    const std::size_t cap = config.links.max_per_scan;
    std::map<int, std::size_t> kept_per_side;
    std::vector<std::size_t> partners;
    for (const auto& [fraction, t] : ranked) {
        if (cap == 0 || kept_per_side[scans[t].side]++ < cap) partners.push_back(t);
    }
    // A link to a scan no longer among the best (the poses moved) gives way.
    std::erase_if(links, [&](const live::Link& l) {
        return l.source == s &&
               std::find(partners.begin(), partners.end(), l.target) == partners.end();
    });
    return partners;
}

bool LiveRegistrar::State::try_link(std::size_t t, std::size_t s, const Pose& initial) {
    link_tried[{t, s}] = initial;
    // A link computed from other poses is replaced by the new attempt (or dropped).
    std::erase_if(links, [&](const live::Link& l) { return l.target == t && l.source == s; });
    FineRegistrationResult fine =
        register_fine(scans[s].cloud, scans[t].cloud, tree_of(t), initial, config.links.fine);
    if (!usable_link(fine, config)) return false;
    link_rms_m.push_back(fine.rms_m);
    links.push_back(
        {.target = t,
         .source = s,
         .correspondences = compress_link(std::move(fine.correspondences), fine.T_target_source,
                                          config.links.max_correspondences)});
    return true;
}

std::size_t LiveRegistrar::State::make_links() {
    std::size_t added = 0;
    for (std::size_t s = 0; s < scans.size(); ++s) {
        if (!live::active(scans[s])) continue;
        // Forecasts are cheap (200 points each): the interrupt is asked per fine registration.
        for (const std::size_t t : link_partners(s)) {
            const Pose initial = scans[t].T_group_scan.inverse() * scans[s].T_group_scan;
            const auto tried = link_tried.find({t, s});
            if (tried != link_tried.end() &&
                live::poses_agree(tried->second, initial, scans[s].centroid_m,
                                  config.links.retry_deg, config.links.retry_m)) {
                continue;
            }
            if (interrupted()) return added;  // Not marked tried: the next call does it.
            added += try_link(t, s, initial);
        }
    }
    return added;
}

}  // namespace anascan::acquisition
