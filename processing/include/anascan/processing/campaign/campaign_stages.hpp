#pragma once
/// \file
/// The pure stages of a scan campaign (many unordered, unlabelled scans of many stones;
/// paper §4.2 at scale). Each stage is a set of independent tasks whose inputs and outputs
/// are plain data, so that a runner may execute them in any order, in one process or over
/// MPI, and store every result as it arrives (acquisition/campaign):
///  1. prepare (per scan): `prepare_campaign_scan` — cleaning and normals as `register`
///     does them, and the figures the later stages need without loading the scan;
///  2. describe (per scan): `describe_campaign_scan` — the scan's global descriptor, a set
///     of hashed, pose- and scale-free triangle keys of its integral-invariant keypoints;
///  3. candidates (once): `propose_candidates` — an inverted index over the keys proposing,
///     for each scan, the few scans sharing the most keys (never all pairs);
///  4. pairwise (per candidate pair): `register_campaign_pair` — global and fine
///     registration with verification (`register_global`: look-alike and slide guards);
///  5. match graph (once): `find_stones` — the per-scan RMS gate, the loop checks over triangles
///  and cycles of verified pairs, then the components: the
///     stones;
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
#include "anascan/processing/features/invariant_keypoints.hpp"
#include "anascan/processing/registration/batch/scan_registration.hpp"

namespace anascan {

/// The match graph's guard against look-alikes: pairs that pass pairwise verification
/// between two stones, or at a wrong pose of one stone (a near-symmetric block turned by
/// 90° or 180°), judged by evidence beyond the single pair.
struct StoneGraphConfig {
    /// Per-scan gate: a pair is cut when its RMS over its target spacing exceeds this
    /// multiple of the least such ratio among the pairs of either of its scans, worst first,
    /// judging the rest again after each cut (each scan's
    /// best pair is measured with its own scanner and resolution; a campaign median mixes
    /// them). True pairs of one scan vary by about 2 (overlap, incidence): measured 1.9 on
    /// the simulated blocks and 2.0 on the bunny's scans; look-alikes fit 2.2 to 8 times worse.
    double relative_rms_gate_factor = 2.5;
    /// A loop of pairs (a triangle, or a pair against the poses its stone's better pairs
    /// give) closes when it leaves at most this rotation ...
    double max_loop_rotation_deg = 2.0;
    /// ... and this many of its scans' coarser sample spacing at the scan's centre (true
    /// loops: within a spacing; a look-alike or a turned fit: tens of degrees and mm).
    double max_loop_spacing_factor = 4.0;
};

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
    /// Triangle partners of each keypoint (nearest keypoints of the same radius).
    std::size_t key_nearest_keypoints = 8;
    /// Descriptor sites and samples are taken by a minimum distance, not on a grid of the
    /// scan's frame (IntegralInvariantConfig::frame_free_sampling); sites this many sample
    /// spacings apart, or this fraction of the smallest radius when that is coarser (bounds
    /// the cost).
    double key_site_spacing_factor = 0.75;
    double key_site_spacing_radius_fraction = 1.0 / 32.0;
    /// The keypoints (extrema of V_r) that the triangles join.
    InvariantKeypointConfig keypoints{};
    /// Candidates: each scan proposes its this many most similar scans; a pair is a
    /// candidate when either scan proposes the other.
    std::size_t candidates_per_scan = 8;
    /// Keys held by more than this many scans tell scans apart too little and get no vote.
    std::size_t max_scans_per_key = 64;
    /// The match graph's look-alike guard.
    StoneGraphConfig graph{};
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
    std::size_t keypoints = 0;  ///< All radii and sides.
    /// Why it has no keys (empty when it has): descriptors invalid, no keypoint triangles (a
    /// plane, the ground or background only).
    std::string problem;
};

/// Integral-invariant descriptors of the prepared scan at radii from its own size (rounded
/// to a ladder of ratio 1.5 shared by the campaign, so scans of one stone mostly share
/// them) at dense sites, their extrema as keypoints (`invariant_keypoints`), and a key per
/// keypoint triangle (a keypoint and two of its nearest): the three side lengths on a log scale,
/// each with its nearer neighbouring bin, and the absolute radius and side of the opposite corners,
/// in a canonical order. Keys do not depend on pose or on the scan's size.
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

/// The stones. Verified pairs pass, in turn: the per-scan gate (not a campaign-wide gate
/// such as `register`'s session gate, a median that mixes scanners); the triangle check (every
/// triangle of pairs must close: in a triangle that does not, the pair of worst RMS ratio among
/// those that close no triangle is cut, until all close); and the cycle check (pairs joined best
/// first, spanning tree style; a pair between two scans already in one stone must agree with the
/// poses the better pairs gave, else it is cut). The stones are the connected components (of two or
/// more scans) of the rest. A scan whose placement rests on a loop that did not close carries a
/// warning.
struct StoneGraph {
    std::vector<std::vector<std::size_t>> stones;  ///< Scan indices, ascending; largest first.
    std::vector<int> stone_of_scan;                ///< -1: in no stone.
    /// Per scan: why its placement is in doubt (empty: no doubt).
    std::vector<std::string> warning_of_scan;
    std::size_t relative_gated_pairs = 0;  ///< Cut by the per-scan gate.
    std::size_t triangle_cut_pairs = 0;    ///< Cut by the triangle check.
    std::size_t cycle_cut_pairs = 0;       ///< Cut by the cycle check.
};

/// `scans` holds each scan's summary (centre and spacing, for the loop tolerances); pair
/// indices refer to it.
StoneGraph find_stones(const std::vector<PreparedSummary>& scans,
                       const std::vector<RegisteredPair>& pairs, const CampaignConfig& config);

}  // namespace anascan
