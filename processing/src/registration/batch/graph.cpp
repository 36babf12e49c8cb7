// Pose graph, pairwise links and multi-view refinement of register_scans.
#include <algorithm>
#include <memory>
#include <numeric>
#include <string>
#include <utility>

#include "anascan/processing/registration/multiview/link_compression.hpp"
#include "registration/batch/steps.hpp"
#include "registration/global/steps.hpp"

namespace anascan::detail {
namespace {

/// Kruskal: verified pairs by decreasing weight (ties by pair order); marks tree edges.
DisjointSets spanning_forest(std::size_t n, std::vector<PairOutcome>& pairs) {
    std::vector<std::size_t> order;
    for (std::size_t p = 0; p < pairs.size(); ++p) {
        if (pairs[p].verified) order.push_back(p);
    }
    std::stable_sort(order.begin(), order.end(), [&](std::size_t a, std::size_t b) {
        return pairs[a].weight > pairs[b].weight;
    });
    DisjointSets sets(n);
    for (std::size_t p : order) pairs[p].in_tree = sets.unite(pairs[p].source, pairs[p].target);
    return sets;
}

/// Numbers the components of the usable scans: largest first, ties by lowest scan index.
std::vector<int> number_groups(const std::vector<bool>& usable, DisjointSets& sets,
                               std::size_t& group_count) {
    const std::size_t n = usable.size();
    std::vector<std::size_t> size(n, 0);
    for (std::size_t i = 0; i < n; ++i) size[sets.find(i)] += usable[i];
    std::vector<std::size_t> roots;
    for (std::size_t i = 0; i < n; ++i) {
        if (usable[i] && sets.find(i) == i) roots.push_back(i);
    }
    std::stable_sort(roots.begin(), roots.end(),
                     [&](std::size_t a, std::size_t b) { return size[a] > size[b]; });
    std::vector<int> group_of_root(n, -1);
    for (std::size_t g = 0; g < roots.size(); ++g) group_of_root[roots[g]] = static_cast<int>(g);
    std::vector<int> group(n, -1);
    for (std::size_t i = 0; i < n; ++i) {
        if (usable[i]) group[i] = group_of_root[sets.find(i)];
    }
    group_count = roots.size();
    return group;
}

/// Poses along the tree edges from each root (the lowest index of its component).
std::vector<Pose> walk_trees(const std::vector<PairOutcome>& pairs, DisjointSets& sets) {
    const std::size_t n = sets.parent.size();
    std::vector<Pose> T_root_scan(n, Pose::Identity());
    std::vector<bool> known(n, false);
    for (std::size_t i = 0; i < n; ++i) known[i] = sets.find(i) == i;
    // A tree has fewer than n edges, so n sweeps over the edges reach every scan.
    for (bool changed = true; changed;) {
        changed = false;
        for (const PairOutcome& p : pairs) {
            if (!p.in_tree || known[p.source] == known[p.target]) continue;
            if (known[p.target]) {
                T_root_scan[p.source] = T_root_scan[p.target] * p.T_target_source;
                known[p.source] = true;
            } else {
                T_root_scan[p.target] = T_root_scan[p.source] * p.T_target_source.inverse();
                known[p.target] = true;
            }
            changed = true;
        }
    }
    return T_root_scan;
}

void copy_fine_figures(const FineRegistrationResult& fine, PairOutcome& pair) {
    pair.fine.status = fine.status;
    pair.fine.iterations = fine.iterations;
    pair.fine.rms_m = fine.rms_m;
    pair.fine.overlap_fraction = fine.overlap_fraction;
    pair.fine.normal_deviation_deg = fine.normal_deviation_deg;
    pair.fine.eigenvalue_ratio = fine.degeneracy.eigenvalue_ratio;
    const Eigen::Vector3d weakest = fine.degeneracy.weakest_direction.tail<3>();
    pair.fine.weakest_translation =
        weakest.norm() > 0.0 ? Eigen::Vector3d(weakest.normalized()) : Eigen::Vector3d::Zero();
    pair.fine.time_s = fine.time_s;
}

/// Scans of one group whose spheres meet (with a margin of the fine search distance).
bool may_overlap(const ScanSummary& a, const Pose& T_root_a, const ScanSummary& b,
                 const Pose& T_root_b, double margin_m) {
    const double gap = (T_root_a * a.centre_m - T_root_b * b.centre_m).norm();
    return gap <= a.radius_m + b.radius_m + margin_m;
}

/// Overlap of two scans' feature sites under the graph poses (a cheap forecast of the fine
/// registration's overlap).
double predicted_overlap(const ScanFeatures& source, const ScanFeatures& target,
                         const KdTree& target_sites, const Pose& T_target_source,
                         const GlobalRegistrationConfig& config) {
    return site_overlap_fraction(
        source.invariants, target.invariants, target_sites, T_target_source,
        config.site_overlap_spacing_factor * target.invariants.site_spacing_m);
}

bool usable_link(const FineRegistrationResult& fine, double target_spacing_m,
                 const ScanRegistrationConfig& config) {
    return (fine.status == FineRegistrationStatus::kConverged ||
            fine.status == FineRegistrationStatus::kMaxIterations) &&
           fine.overlap_fraction >= config.min_link_overlap_fraction &&
           fine.degeneracy.eigenvalue_ratio >= config.fine.degeneracy_threshold &&
           fine.normal_deviation_deg.value_or(0.0) <= config.global.max_normal_deviation_deg &&
           fine.rms_m <= config.max_link_rms_spacing_factor * target_spacing_m;
}

/// One group's scans (ascending) and its links re-indexed to positions in `members`.
struct GroupLinks {
    std::vector<std::size_t> members;
    std::vector<MultiviewLink> links;
    std::vector<std::size_t> pairs;  ///< Pair index of each link.
};

/// Moves group g's links out of `links` (each link belongs to one group).
GroupLinks collect_group(PairLinks& links, const PoseGraph& graph, int g) {
    GroupLinks group;
    std::vector<std::size_t> local(graph.group.size(), 0);
    for (std::size_t i = 0; i < graph.group.size(); ++i) {
        if (graph.group[i] != g) continue;
        local[i] = group.members.size();
        group.members.push_back(i);
    }
    for (std::size_t l = 0; l < links.links.size(); ++l) {
        MultiviewLink& link = links.links[l];
        if (graph.group[link.target_index] != g) continue;
        group.links.push_back({.target_index = local[link.target_index],
                               .source_index = local[link.source_index],
                               .correspondences = std::move(link.correspondences)});
        group.pairs.push_back(links.pair_of_link[l]);
    }
    return group;
}

}  // namespace

PoseGraph build_pose_graph(const std::vector<bool>& usable, std::vector<PairOutcome>& pairs) {
    PoseGraph graph;
    DisjointSets sets = spanning_forest(usable.size(), pairs);
    graph.group = number_groups(usable, sets, graph.group_count);
    graph.T_root_scan = walk_trees(pairs, sets);
    return graph;
}

PairLinks make_links(PreparedScans& scans, const PoseGraph& graph, std::vector<PairOutcome>& pairs,
                     const ScanRegistrationConfig& config, const RegistrationProgress& progress) {
    FineRegistrationConfig fine_config = config.fine;
    fine_config.keep_correspondences = true;
    PairLinks links;
    std::size_t tree_scan = scans.size();  // Target of the cached site tree.
    ScanFeatures target_f;
    std::unique_ptr<KdTree> target_sites;
    for (std::size_t p = 0; p < pairs.size(); ++p) {
        PairOutcome& pair = pairs[p];
        const std::size_t s = pair.source, t = pair.target;
        if (graph.group[s] < 0 || graph.group[s] != graph.group[t]) continue;
        if (!may_overlap(scans.summary[s], graph.T_root_scan[s], scans.summary[t],
                         graph.T_root_scan[t], config.fine.max_correspondence_distance_m)) {
            continue;
        }
        if (tree_scan != t) {  // Rebuilt only when the target changes.
            target_f = scans.full_features(t);
            target_sites = std::make_unique<KdTree>(target_f.invariants.site_positions);
            tree_scan = t;
        }
        const Pose initial = graph.T_root_scan[t].inverse() * graph.T_root_scan[s];
        if (predicted_overlap(scans.full_features(s), target_f, *target_sites, initial,
                              config.global) < config.min_link_overlap_fraction) {
            continue;
        }
        FineRegistrationResult fine =
            register_fine(*scans.cloud(s), *scans.cloud(t), initial, fine_config);
        copy_fine_figures(fine, pair);
        if (progress) {
            progress("fine registration: scan " + std::to_string(s) + " onto " + std::to_string(t) +
                     ": " + std::string(to_string(fine.status)));
        }
        if (!usable_link(fine, scans.spacing_m[t], config)) continue;
        pair.linked = true;
        links.links.push_back(
            {.target_index = t,
             .source_index = s,
             .correspondences = compress_link(std::move(fine.correspondences), fine.T_target_source,
                                              config.max_link_correspondences)});
        links.pair_of_link.push_back(p);
    }
    return links;
}

MultiviewStatus refine_groups(PairLinks links, const MultiviewRefinementConfig& config,
                              PoseGraph& graph, std::vector<PairOutcome>& pairs) {
    MultiviewStatus largest_status = MultiviewStatus::kConverged;
    for (int g = 0; g < static_cast<int>(graph.group_count); ++g) {
        const GroupLinks group = collect_group(links, graph, g);
        if (group.members.size() < 2 || group.links.empty()) continue;
        std::vector<Pose> poses;
        for (std::size_t i : group.members) poses.push_back(graph.T_root_scan[i]);
        MultiviewRefinementConfig group_config = config;
        group_config.fixed_scan_index = 0;  // The group's lowest-index scan.
        const MultiviewRefinementResult refined =
            refine_multiview(poses, group.links, group_config);
        if (g == 0) largest_status = refined.status;
        for (std::size_t l = 0; l < group.pairs.size(); ++l) {
            pairs[group.pairs[l]].link_dropped = refined.links[l].dropped;
        }
        const bool usable = refined.status == MultiviewStatus::kConverged ||
                            refined.status == MultiviewStatus::kMaxRounds ||
                            refined.status == MultiviewStatus::kDisconnected;
        if (!usable) continue;  // Keep the spanning-tree poses.
        for (std::size_t m = 0; m < group.members.size(); ++m) {
            graph.T_root_scan[group.members[m]] = refined.T_world_scan[m];
        }
    }
    return largest_status;
}

}  // namespace anascan::detail
