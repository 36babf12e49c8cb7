#pragma once
// Internal steps of register_scans (scan_registration.cpp, scan_registration_graph.cpp).
#include <chrono>
#include <cstddef>
#include <vector>

#include "anascan/processing/scan_registration.hpp"

namespace anascan::detail {

/// Seconds since `start` (steady clock).
double seconds_since(std::chrono::steady_clock::time_point start);

/// Connected components of the verified pairs and the spanning-tree poses within each.
struct PoseGraph {
    std::vector<int> group;         ///< Per scan: 0 = largest component; -1 = not usable.
    std::vector<Pose> T_root_scan;  ///< Per scan: into its group's first scan's frame.
    std::size_t group_count = 0;
};

/// Maximum spanning forest (Kruskal) over the verified pairs by weight, marking the tree
/// edges, then poses by walking each tree from its lowest-index scan.
PoseGraph build_pose_graph(const std::vector<bool>& usable, std::vector<PairOutcome>& pairs);

/// Multi-view links (scan indices) and, per link, the index of its pair.
struct PairLinks {
    std::vector<MultiviewLink> links;
    std::vector<std::size_t> pair_of_link;
};

/// Final fine registration of every verified pair from the graph poses; fills the pairs'
/// fine figures and returns one link per pair good enough.
PairLinks make_links(const std::vector<PointCloud>& clouds, const PoseGraph& graph,
                     std::vector<PairOutcome>& pairs, const ScanRegistrationConfig& config,
                     const RegistrationProgress& progress);

/// Multi-view refinement of each group with more than one scan, in place on
/// `graph.T_root_scan`; marks dropped links. Returns the largest group's status.
MultiviewStatus refine_groups(const PairLinks& links, const MultiviewRefinementConfig& config,
                              PoseGraph& graph, std::vector<PairOutcome>& pairs);

}  // namespace anascan::detail
