#pragma once
/// \file
/// The pure stages of a scan campaign (many unordered, unlabelled scans of many stones;
/// paper §4.2 at scale). Each stage is a set of independent tasks whose inputs and outputs
/// are plain data, so that a runner may execute them in any order, in one process or over
/// MPI, and store every result as it arrives (acquisition/campaign):
///  1. prepare (per scan): `prepare_campaign_scan` — cleaning and normals as `register`
///     does them, and the figures the later stages need without loading the scan;
///  2. describe (per scan): `describe_campaign_scan` — the scan's global descriptor, a set
///     of hashed, pose- and scale-free feature-triangle keys of its integral-invariant patches;
///  3. candidates (once): `propose_candidates` — an inverted index over the keys proposing,
///     for each scan, the few scans sharing the most keys (never all pairs);
///  4. pairwise (per candidate pair): `register_campaign_pair` — global and fine
///     registration with verification (`register_global`: look-alike and slide guards);
///  5. match graph (once): `find_stones` — the campaign RMS gate, then connected
///     components of the verified pairs: the stones;
///  6. multi-view (per stone): `register_scans` on the stone's prepared scans.
/// Thread safety: every function is reentrant. Results do not depend on thread count.
#include <Eigen/Core>
#include <cstddef>
#include <cstdint>
#include <string>
#include <utility>
#include <vector>

#include "anascan/processing/core/point_cloud.hpp"
#include "anascan/processing/core/pose.hpp"
#include "anascan/processing/registration/batch/scan_registration.hpp"

namespace anascan {

/// Settings of the campaign stages. Callers use designated initialisers.
struct CampaignConfig {
    /// Preparation (normals, orientation without a sensor, down-sampling) and the per-stone
    /// multi-view stage; its `global` settings are used by the pairwise stage.
    ScanRegistrationConfig registration{};
    /// A prepared scan with fewer points is not used.
    std::size_t min_scan_points = 500;
    /// Descriptor: triangle sides are quantised on a log scale with this ratio between
    /// neighbouring bins (scale-free, so scans of stones of any size share one index).
    double key_length_ratio = 1.1;
    /// Triangle partners of each patch (nearest patches of the same radius).
    std::size_t key_nearest_patches = 8;
    /// Candidates: each scan proposes its this many most similar scans; a pair is a
    /// candidate when either scan proposes the other.
    std::size_t candidates_per_scan = 8;
    /// Keys held by more than this many scans tell scans apart too little and get no vote.
    std::size_t max_scans_per_key = 64;
};

/// What the later stages need of a prepared scan, without loading it.
struct PreparedSummary {
    std::size_t points = 0;                              ///< After preparation.
    double spacing_m = 0.0;                              ///< Median sample spacing.
    Eigen::Vector3d centre_m = Eigen::Vector3d::Zero();  ///< Bounding box centre, own frame.
    double diagonal_m = 0.0;                             ///< Bounding box diagonal.
    std::uint64_t position_hash = 0;  ///< Of the prepared positions (finds duplicate scans).
    bool normals_estimated = false;
    /// Why the scan cannot be used (empty when usable): too few points, no extent.
    std::string problem;
};

/// Prepares `cloud` in place (`prepare_scan`: finite points, normals estimated and oriented
/// as seen from the side the scan shows, voxel down-sampling) and summarises it. Plain
/// points in an unknown frame are the expected input; normals given are kept.
PreparedSummary prepare_campaign_scan(PointCloud& cloud, const CampaignConfig& config);

/// A scan's global descriptor: sorted distinct 64-bit keys.
struct ScanDescriptor {
    std::vector<std::uint64_t> keys;
    std::size_t patches = 0;  ///< Feature patches of the middle saliency level.
    /// Why it has no keys (empty when it has): descriptors invalid, no feature patches (a
    /// plane, the ground or background only).
    std::string problem;
};

/// Integral-invariant descriptors of the prepared scan at radii from its own size (rounded
/// to a ladder of ratio 1.5 shared by the campaign, so scans of one stone mostly share
/// them), patches at the scan's own saliency levels, and a key per feature triangle (a
/// patch and two of its nearest): the three side lengths on a log scale, each with its
/// nearer neighbouring bin, and the absolute radius and side of the opposite corners, in a
/// canonical order. Keys do not depend on pose or on the scan's size.
ScanDescriptor describe_campaign_scan(const PointCloud& prepared, double spacing_m,
                                      const CampaignConfig& config);

/// A candidate pair (source > target, scan indices) and its similarity.
struct CandidatePair {
    std::size_t source = 0, target = 0;
    double similarity = 0.0;  ///< Idf-weighted shared keys / sqrt(keys_s keys_t).
};

/// The candidate pairs of scans with these descriptors (empty key sets take no part),
/// sorted by (source, target).
std::vector<CandidatePair> propose_candidates(const std::vector<std::vector<std::uint64_t>>& keys,
                                              const CampaignConfig& config);

/// One pair's registration, as the match graph needs it.
struct CampaignPairResult {
    GlobalRegistrationStatus status = GlobalRegistrationStatus::kInvalidInput;
    bool verified = false;                    ///< Status success.
    Pose T_target_source = Pose::Identity();  ///< When verified.
    double rms_m = 0.0;
    double overlap_fraction = 0.0;
    double target_spacing_m = 0.0;
    bool slide_ambiguous = false;
    double time_s = 0.0;
};

/// Global registration of `source` onto `target` (prepared clouds), fine registration and
/// verification of its hypotheses (`register_global` with config.registration.global).
CampaignPairResult register_campaign_pair(const PointCloud& source, const PointCloud& target,
                                          const CampaignConfig& config);

/// A pair's result with its scans, for `find_stones`.
struct RegisteredPair {
    std::size_t source = 0, target = 0;
    CampaignPairResult result;
};

/// The stones: connected components (of two or more scans) of the verified pairs within
/// the campaign RMS gate (ScanRegistrationConfig::session_rms_gate_factor over the whole
/// campaign).
struct StoneGraph {
    std::vector<std::vector<std::size_t>> stones;  ///< Scan indices, ascending; largest first.
    std::vector<int> stone_of_scan;                ///< -1: in no stone.
    double rms_gate_m = 0.0;                       ///< Infinity when off.
    std::size_t gated_pairs = 0;                   ///< Verified pairs above the gate.
};

StoneGraph find_stones(std::size_t scan_count, const std::vector<RegisteredPair>& pairs,
                       const CampaignConfig& config);

}  // namespace anascan
