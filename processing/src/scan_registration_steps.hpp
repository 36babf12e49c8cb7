#pragma once
// Internal steps of register_scans (scan_registration.cpp, scan_registration_graph.cpp).
#include <algorithm>
#include <chrono>
#include <cstddef>
#include <numeric>
#include <span>
#include <vector>

#include "anascan/processing/scan_registration.hpp"

namespace anascan::detail {

/// Seconds since `start` (steady clock).
double seconds_since(std::chrono::steady_clock::time_point start);

/// Union-find with path halving; a set's root is its lowest index.
struct DisjointSets {
    std::vector<std::size_t> parent;
    explicit DisjointSets(std::size_t n) : parent(n) {
        std::iota(parent.begin(), parent.end(), std::size_t{0});
    }
    std::size_t find(std::size_t i) {
        while (parent[i] != i) i = parent[i] = parent[parent[i]];
        return i;
    }
    bool unite(std::size_t a, std::size_t b) {
        a = find(a);
        b = find(b);
        if (a == b) return false;
        parent[std::max(a, b)] = std::min(a, b);
        return true;
    }
};

/// The prepared clouds (empty: not usable), their median sample spacings (metres) and
/// their features (filled by the features stage).
struct PreparedScans {
    std::vector<PointCloud> clouds;
    std::vector<double> spacing_m;
    std::vector<ScanFeatures> features;
};

/// Loads and prepares every scan (one full cloud in memory at a time); fills the outcomes'
/// point counts, spacings and, for unusable scans, the reason.
PreparedScans load_and_prepare(const std::vector<ScanInput>& inputs,
                               const ScanRegistrationConfig& config,
                               const RegistrationProgress& progress,
                               ScanRegistrationResult& result);

/// Adds a warning to every placed scan whose prepared points equal an earlier scan's.
void warn_identical_scans(const PreparedScans& scans, ScanRegistrationResult& result);

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

/// Final fine registration, from the graph poses, of every pair of one group whose bounding
/// spheres meet; fills the pairs' fine figures and returns one link per pair good enough.
PairLinks make_links(const PreparedScans& scans, const PoseGraph& graph,
                     std::vector<PairOutcome>& pairs, const ScanRegistrationConfig& config,
                     const RegistrationProgress& progress);

/// Multi-view refinement of each group with more than one scan, in place on
/// `graph.T_root_scan`; marks dropped links. Returns the largest group's status.
MultiviewStatus refine_groups(const PairLinks& links, const MultiviewRefinementConfig& config,
                              PoseGraph& graph, std::vector<PairOutcome>& pairs);

}  // namespace anascan::detail
