#pragma once
// Internal steps of register_scans (scan_registration.cpp, scan_registration_graph.cpp).
#include <algorithm>
#include <chrono>
#include <cstddef>
#include <cstdint>
#include <functional>
#include <memory>
#include <numeric>
#include <optional>
#include <set>
#include <span>
#include <string>
#include <utility>
#include <vector>

#include "anascan/processing/core/stopwatch.hpp"
#include "anascan/processing/registration/batch/scan_registration.hpp"
#include "anascan/processing/spatial/cloud_store.hpp"
#include "registration/batch/records.hpp"

namespace anascan::detail {

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

/// What the later stages need of a prepared cloud without loading it.
struct ScanSummary {
    std::size_t points = 0;                              ///< 0: not usable.
    Eigen::Vector3d centre_m = Eigen::Vector3d::Zero();  ///< Bounding sphere, own frame.
    double radius_m = 0.0;
    double diagonal_m = 0.0;  ///< Local bounds' diagonal.
    std::uint64_t position_hash = 0;
};

/// FNV-1a over the origin and local positions: equal clouds give equal hashes.
std::uint64_t position_hash(const PointCloud& cloud);

/// Bounding sphere, diagonal and hash of a prepared cloud (points left to the caller).
ScanSummary summarize(const PointCloud& cloud);

/// The prepared clouds (in `store` under key 2i; not there: not usable), their summaries,
/// median sample spacings (metres) and features (filled by the features stage). When
/// spilling, the features' sites live in `store` under key 2i + 1 and `features` holds
/// only the patches and figures (see `full_features`).
struct PreparedScans {
    CloudStore store;
    std::vector<ScanSummary> summary;
    std::vector<double> spacing_m;
    /// Sensor positions (scan frame, metres) known exactly (ScanInput::sensor_origin_known).
    std::vector<std::optional<Eigen::Vector3d>> viewpoint_m;
    std::vector<ScanFeatures> features;
    std::string spill_error;                ///< The first store failure.
    std::filesystem::path spill_directory;  ///< Empty: everything in memory.
    /// When spilling, each scan's patches wait here (record `patch_record[i]`) and
    /// `features[i].patches` keeps only the status and counts.
    RecordFile patch_records;
    std::vector<std::size_t> patch_record;

    std::size_t size() const { return summary.size(); }
    bool usable(std::size_t i) const { return summary[i].points > 0; }
    /// Scan i's prepared cloud (empty when it cannot be had; the failure is recorded).
    std::shared_ptr<const PointCloud> cloud(std::size_t i);
    /// Scan i's features with their sites and patches (reloaded when spilled).
    ScanFeatures full_features(std::size_t i);
    /// Scan i's patches (reloaded when spilled).
    FeaturePatchResult patches(std::size_t i);
};

/// Loads and prepares every scan (one full cloud in memory at a time); fills the outcomes'
/// point counts, spacings and, for unusable scans, the reason.
PreparedScans load_and_prepare(const std::vector<ScanInput>& inputs,
                               const ScanRegistrationConfig& config,
                               const RegistrationProgress& progress,
                               ScanRegistrationResult& result);

/// Adds a warning to every placed scan whose prepared points equal an earlier scan's.
void warn_identical_scans(PreparedScans& scans, ScanRegistrationResult& result);

/// Adds a warning to every placed scan all of whose links ended still moving along a weak
/// direction (ScanRegistrationConfig::sliding_link_max_eigenvalue_ratio).
void warn_sliding_scans(const ScanRegistrationConfig& config, ScanRegistrationResult& result);

/// Adds a warning to every placed scan (of three or more) kept by fewer than two links:
/// no second scan confirms its pose, so a look-alike fit would go unnoticed.
void warn_unconfirmed_scans(ScanRegistrationResult& result);

/// Descriptors and patches of every usable scan (features stage). In memory: descriptors
/// of all scans, saliency levels pooled over all sites. Spilling: two passes, descriptors
/// on disk in between, levels pooled over at most `max_level_sites_per_scan` sites a scan.
void describe_all(PreparedScans& scans, const ScanRegistrationConfig& config,
                  const RegistrationProgress& progress);

/// One key held by one scan, in an inverted index of descriptor keys (sorted by key, then
/// scan).
struct IndexEntry {
    std::uint64_t key = 0;
    std::uint32_t scan = 0;
    std::uint32_t unused = 0;  // Written to files: no uninitialised padding.
    bool operator<(const IndexEntry& o) const { return key != o.key ? key < o.key : scan < o.scan; }
};

/// Pair pruning's similarity of every two scans: idf-weighted shared feature-triangle
/// keys (lower triangle, float) and each scan's key count.
struct PairVotes {
    std::size_t n = 0;  ///< Scans; 0 when nothing was pruned.
    std::vector<float> votes;
    std::vector<std::uint32_t> key_count;

    static std::size_t index(std::size_t i, std::size_t j) {
        if (i < j) std::swap(i, j);
        return i * (i - 1) / 2 + j;
    }
    float& at(std::size_t i, std::size_t j) { return votes[index(i, j)]; }
    /// Adds the idf weight log(n / holders) of every key held by 2..max_holders scans to
    /// each pair of its holders; `sorted` holds every entry of its keys, sorted.
    void add_shared_keys(std::span<const IndexEntry> sorted, std::size_t max_holders);
    /// votes / sqrt(keys_i keys_j); 0 when they share no informative key.
    double similarity(std::size_t i, std::size_t j) const;
    /// Scan i's `count` most similar scans j (similarity > 0) with `eligible(j)`, best
    /// first, ties by index.
    std::vector<std::size_t> most_similar(std::size_t i, std::size_t count,
                                          const std::function<bool(std::size_t)>& eligible) const;
};

/// The indices of the `count` smallest keys of (key, index) pairs (ties by index), smallest
/// first.
template <typename Key>
std::vector<std::size_t> smallest(std::vector<std::pair<Key, std::size_t>> keyed,
                                  std::size_t count) {
    const std::size_t keep = std::min(count, keyed.size());
    std::partial_sort(keyed.begin(), keyed.begin() + static_cast<std::ptrdiff_t>(keep),
                      keyed.end());
    std::vector<std::size_t> out;
    for (std::size_t r = 0; r < keep; ++r) out.push_back(keyed[r].second);
    return out;
}

struct CandidatePairs {
    std::vector<std::pair<std::size_t, std::size_t>> pairs;  ///< Source > target, sorted.
    PairVotes votes;
};

/// The pairs to match (source > target, in pair order): all of them, or, when
/// `max_candidates_per_scan` > 0, the pairs where either scan is among the other's most
/// similar. The keys wait in files of the spill directory (when set) so that only a
/// bucket of them is in memory; a file failure is recorded and gives no pairs.
CandidatePairs candidate_pairs(PreparedScans& scans, const ScanRegistrationConfig& config);

/// The session RMS gate (metres): session_rms_gate_factor times the median over scans of
/// each scan's least verified pair RMS; infinity when off or with too few such scans.
double session_rms_gate_m(const std::vector<PairOutcome>& pairs, std::size_t scan_count,
                          const ScanRegistrationConfig& config);

/// Un-verifies a verified pair whose RMS exceeds `gate_m` (marks it above_rms_gate).
/// Returns whether it did.
bool apply_rms_gate(PairOutcome& pair, double gate_m);

/// Connected components of the verified pairs and the spanning-tree poses within each.
struct PoseGraph {
    std::vector<int> group;         ///< Per scan: 0 = largest component; -1 = not usable.
    std::vector<Pose> T_root_scan;  ///< Per scan: into its group's first scan's frame.
    std::size_t group_count = 0;
};

/// Maximum spanning forest (Kruskal) over the verified pairs by weight, marking the tree
/// edges, then poses by walking each tree from its lowest-index scan.
PoseGraph build_pose_graph(const std::vector<bool>& usable, std::vector<PairOutcome>& pairs);

/// Pairs that may join the groups of `graph` (bridging, see scan_registration_bridging.cpp):
/// each group's `bridge_scans_per_group` border scans (fewest members close by) with their
/// `bridge_partners_per_scan` most similar scans of other groups not in `matched`
/// (source > target, sorted).
std::vector<std::pair<std::size_t, std::size_t>> bridge_pairs(
    const PairVotes& votes, const PoseGraph& graph, const std::vector<ScanSummary>& summary,
    const std::set<std::pair<std::size_t, std::size_t>>& matched,
    const ScanRegistrationConfig& config);

/// Multi-view links (scan indices) and, per link, the index of its pair.
struct PairLinks {
    std::vector<MultiviewLink> links;
    std::vector<std::size_t> pair_of_link;
};

/// Final fine registration, from the graph poses, of every pair of one group whose bounding
/// spheres meet; fills the pairs' fine figures and returns one link per pair good enough.
PairLinks make_links(PreparedScans& scans, const PoseGraph& graph, std::vector<PairOutcome>& pairs,
                     const ScanRegistrationConfig& config, const RegistrationProgress& progress);

/// Multi-view refinement of each group with more than one scan (the links' correspondences
/// are moved, not copied, into each group's system), in place on
/// `graph.T_root_scan`; marks dropped links. Returns the largest group's status.
MultiviewStatus refine_groups(PairLinks links, const MultiviewRefinementConfig& config,
                              PoseGraph& graph, std::vector<PairOutcome>& pairs);

}  // namespace anascan::detail
