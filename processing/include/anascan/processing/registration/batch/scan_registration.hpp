#pragma once
/// \file
/// Registration of N unordered scans without initial poses (paper §4, batch form):
///  1. prepare: every scan loaded once, non-finite points dropped, normals estimated and
///     oriented (unless given);
///  2. features: integral-invariant descriptors and patches of each scan, computed once at
///     radii shared by all scans (from the largest scan) and saliency levels pooled over all;
///  3. matching: `match_features` for every pair (cheap: patches only);
///  4. pairwise: pairs in decreasing order of their best consensus score are refined and
///     verified (`register_global` minus the features) until their two scans are connected
///     through verified pairs; pairs whose scans are already connected are skipped; then
///     verified pairs above the session RMS gate are dropped and the skipped pairs refined
///     under it (`session_rms_gate_factor`); with
///     pruning, bridging rounds then match the border scans of the groups left with their
///     most similar scans of other groups;
///  5. pose graph: the verified pairs form a spanning forest giving initial poses;
///  6. links: every pair of a group whose bounding spheres meet under those poses is fine
///     registered from them, keeping its correspondences; a converged pair with enough
///     overlap, agreeing normals and an RMS within the verification limit becomes a link;
///  7. multi-view: `refine_multiview` solves for all poses of a group at once.
/// Groups are connected components; the largest group's first scan (input order) is the
/// world frame and only the largest group's scans are placed. A scan that is not placed is
/// reported with the reason. See docs/scan-registration.md.
///
/// Cost: N features, N(N-1)/2 feature matchings (~0.05 s each for 40k-point scans; about
/// k N with pruning), about N-1 to a few N refinements, and the links' fine registrations.
///
/// Memory: each scan's loader is called exactly once, in input order, and the full cloud is
/// released right after preparation; only the prepared clouds (down-sampled to
/// `ScanRegistrationConfig::voxel_size_m` when that is positive) and their features are kept,
/// or, with `spill_directory`, only a few figures per scan while clouds, sites, patches,
/// pruning keys and matching results wait on disk (at most `max_loaded_clouds` clouds
/// loaded). The multi-view stage needs only the stored correspondences. For thousands of
/// scans see `max_candidates_per_scan` (pair pruning) and `bridge_rounds`.
///
/// Thread safety: `register_scans` is reentrant; it calls `progress` from the calling
/// thread only. Results do not depend on the number of threads.
#include <Eigen/Core>
#include <cstddef>
#include <filesystem>
#include <functional>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "anascan/processing/cleaning/normals.hpp"
#include "anascan/processing/cleaning/view_side.hpp"
#include "anascan/processing/core/expected.hpp"
#include "anascan/processing/core/point_cloud.hpp"
#include "anascan/processing/core/pose.hpp"
#include "anascan/processing/registration/fine/fine_registration.hpp"
#include "anascan/processing/registration/global/global_registration.hpp"
#include "anascan/processing/registration/multiview/multiview_refinement.hpp"

namespace anascan {

/// One scan to register: its name (for reports) and how to load it.
struct ScanInput {
    std::string name;
    /// Returns the scan in its own frame (metres). Called once. Normals, when the cloud has
    /// them, are kept as they are (they must point out of the solid, e.g. toward the sensor).
    std::function<Expected<PointCloud>()> load;
    /// Sensor position in the scan's own frame (metres), used to orient estimated normals;
    /// without it they are oriented as seen from the side the scan shows its convex face to
    /// (orient_as_range_scan: the input is one range scan).
    std::optional<Eigen::Vector3d> sensor_origin_scan_m;
    /// True when sensor_origin_scan_m is where the scan was taken from (a session's record,
    /// a simulation, an explicit `--sensor-origin`), not a guess for orienting normals: then
    /// the pairwise verification also rejects poses that put the other scan's points where
    /// this sensor saw empty space (GlobalRegistrationConfig::free_space).
    bool sensor_origin_known = false;
};

/// Settings of `register_scans`. Callers use designated initialisers.
struct ScanRegistrationConfig {
    NormalEstimationConfig normals{};  ///< For scans loaded without normals.
    /// Orienting estimated normals without a sensor position: the side each scan was seen
    /// from (orient_as_range_scan).
    ViewSideConfig view_side{};
    /// Prepared clouds are voxel down-sampled to this edge length (metres); 0 keeps them
    /// whole. Global and fine registration sample the clouds themselves.
    double voxel_size_m = 0.0;
    GlobalRegistrationConfig global{};  ///< Pairwise stage, every pair.
    /// Final pairwise refinement from the spanning-tree poses (correspondences are kept
    /// whatever `keep_correspondences` says). The graph poses are already close, so the
    /// gate may shrink to 2 mm (4 bunny spacings): measured on the bunny (3 seeds) this cut
    /// the largest translation error at the scan centroids from 0.91-0.98 mm to 0.62-0.67 mm
    /// (rotation 0.22-0.31° → 0.31-0.33°). See docs/scan-registration.md.
    FineRegistrationConfig fine{.min_correspondence_distance_m = 0.002};
    /// Scans with fewer points after preparation are not used (too few for descriptors).
    std::size_t min_scan_points = 100;
    /// Pairs whose final fine registration overlaps less than this fraction (of the source
    /// samples) give no multi-view link.
    double min_link_overlap_fraction = 0.1;
    /// Links also need a mean normal deviation within global.max_normal_deviation_deg and
    /// an RMS within this many target sample spacings (the links' correspondences reach
    /// farther than the verification's, so the limit is looser).
    double max_link_rms_spacing_factor = 2.0;
    MultiviewRefinementConfig multiview{};  ///< fixed_scan_index is set per group.
    /// Session RMS gate: a verified pair counts only when its RMS is at most this multiple
    /// of the session's typical RMS, the median over scans of each scan's least verified
    /// pair RMS (after a first pass of the pairwise stage; pairs skipped in it are then
    /// refined under the gate). Look-alike poses (a box turned by 90° or 180°) pass the
    /// pairwise verification (RMS within a sample spacing) at 3-4 times the RMS of the true
    /// poses of the same session. 0: off. The live registrar has the same gate
    /// (LiveRegistrationConfig::global_rms_median_factor).
    double session_rms_gate_factor = 2.5;
    /// ... and never below this fraction of the scans' sample spacing (the median over the
    /// verified pairs): on clean data the RMS of true pairs is a few micrometres and their
    /// ratios mean nothing (a true pair of less overlap fits 2.6x worse), while look-alikes
    /// fit at about a sample spacing (0.8-1.0 mm at 1 mm spacing, true pairs 0.2-0.25 mm).
    double session_rms_gate_min_spacing_fraction = 0.3;
    /// The gate needs at least this many scans with a verified pair.
    std::size_t min_scans_for_rms_gate = 4;
    /// When every usable scan's sensor origin is known (ScanInput::sensor_origin_known) and
    /// there are at most this many scans, the first pairwise pass refines every matched pair
    /// instead of skipping pairs already connected, so that the session RMS gate is taken
    /// from each scan's best pair. In a session of a block turned over on the ground, the
    /// pairs across the turn fit best at the flipped pose that keeps the ground in place
    /// (0.8-1.0 mm RMS on the ray-cast block, free space respected); refined first (high
    /// consensus scores), they connected the scans before any true pair (0.09-0.25 mm) was
    /// refined and set the gate to 2 mm. 0: never.
    std::size_t full_pairwise_max_scans = 40;
    /// A placed scan all of whose multi-view links ended still moving (max_iterations) along
    /// a weak direction (degeneracy eigenvalue ratio below this) gets a warning naming the
    /// direction: its overlaps do not fix its pose along it. Before the slide probes
    /// (GlobalRegistrationConfig::slide_probe_max_eigenvalue_ratio) a ray-cast block scan was
    /// placed 28 mm slid along the block through two such links (ratios 0.002 and 0.004);
    /// the true neighbour links of that session converge (docs/scan-registration.md
    /// "Slides"). 0: off.
    double sliding_link_max_eigenvalue_ratio = 0.02;

    // ---- Scale (thousands of scans; see docs/scan-registration.md "Scale") ----------------
    /// Pair pruning: 0 matches every pair (N(N-1)/2 matchings). Otherwise each scan is
    /// matched only with its `max_candidates_per_scan` most similar scans by shared
    /// pose-invariant feature triangles (idf-weighted); a pair is matched when either of its
    /// scans lists the other.
    std::size_t max_candidates_per_scan = 0;
    /// Out-of-core: when set, prepared clouds and feature sites are written to this
    /// directory (created when missing, files removed at the end) and reloaded on demand,
    /// at most `max_loaded_clouds` in memory; descriptors are kept on disk between the two
    /// feature passes; patches, pruning keys and matching results wait there too. Empty:
    /// everything stays in memory.
    std::filesystem::path spill_directory;
    std::size_t max_loaded_clouds = 8;  ///< Clouds and site sets held in memory when spilling.
    /// Sites pooled per scan for the saliency levels when spilling (evenly thinned).
    std::size_t max_level_sites_per_scan = 500;
    /// ... and at most this many over all scans (fewer per scan beyond 100 scans), so that
    /// the pooled sites do not grow with the number of scans.
    std::size_t max_level_sites_total = 50000;
    /// Pairwise stage: a pair is not refined once one of its scans has failed this many
    /// refinements (0 = no limit). With pruning, a scan whose true partners failed would
    /// otherwise have all its remaining candidates refined, each failing slowly.
    std::size_t max_failed_refinements_per_scan = 0;
    /// Correspondences a multi-view link keeps (`compress_link`: evenly thinned, with the
    /// optimum of all of them; 0 = all of them).
    std::size_t max_link_correspondences = 0;
    /// Bridging (with pruning only; without pruning every pair is matched anyway): while the
    /// verified pairs leave several groups, up to `bridge_rounds` rounds match and verify,
    /// for the `bridge_scans_per_group` scans of each group with the fewest group members
    /// close by (its border under the spanning-tree poses), their `bridge_partners_per_scan`
    /// most similar (pruning votes) border scans of other groups not matched yet. 0: off.
    std::size_t bridge_rounds = 4;
    std::size_t bridge_scans_per_group = 4;
    std::size_t bridge_partners_per_scan = 2;
};

/// One scan's outcome.
struct ScanOutcome {
    std::string name;
    bool placed = false;  ///< In the largest group: T_world_scan is a result.
    std::string reason;   ///< Why it is not placed (empty when placed).
    /// Something to check although it is placed (e.g. the same points as another scan).
    std::string warning;
    int group = -1;  ///< Connected component (0 = largest); -1 when not loaded.
    /// Maps scan points into the world frame (placed) or into the frame of its group's
    /// first scan (other groups). Identity and meaningless when group is -1.
    Pose T_world_scan = Pose::Identity();
    std::size_t point_count = 0;     ///< After preparation (and down-sampling).
    double spacing_m = 0.0;          ///< Median sample spacing after preparation, metres.
    bool normals_estimated = false;  ///< False when the loaded cloud had normals.
};

/// One pair's figures: feature matching and, unless skipped, global registration of
/// `source` onto `target` (source > target); then, for pairs of one group, the final fine
/// registration from the graph poses.
/// A pair's global registration (paper §4.2.1) as the pairwise stage left it.
struct PairGlobalFigures {
    GlobalRegistrationStatus status = GlobalRegistrationStatus::kInvalidInput;
    /// Not refined: its scans were already connected by verified pairs of higher score (or
    /// one of them had max_failed_refinements_per_scan failures).
    bool skipped = false;
    bool refined = false;           ///< Refined and verified (not skipped, or not any more).
    double rms_m = 0.0;             ///< Point-to-plane RMS of the global result, metres.
    double target_spacing_m = 0.0;  ///< Median target sample spacing, metres.
    double overlap_fraction = 0.0;
    double time_s = 0.0;
};

/// Slide probes of a pair's global pose (GlobalRegistrationConfig::
/// slide_probe_max_eigenvalue_ratio): how many were refined and whether a slid pose fitted
/// alike (ambiguous: the overlap does not fix the pose along a direction, by up to slide_m
/// metres).
struct PairSlides {
    std::size_t probes = 0;
    bool ambiguous = false;
    double slide_m = 0.0;
};

/// The final fine registration of a pair from the graph poses (pairs of one group whose
/// bounding spheres meet; status invalid_input otherwise).
struct PairFineFigures {
    FineRegistrationStatus status = FineRegistrationStatus::kInvalidInput;
    int iterations = 0;
    double rms_m = 0.0;
    double overlap_fraction = 0.0;
    std::optional<double> normal_deviation_deg;
    double eigenvalue_ratio = 0.0;  ///< Degeneracy figure of the final fine registration.
    /// Translation part of its weakest direction (target frame, unit; zero when none).
    Eigen::Vector3d weakest_translation = Eigen::Vector3d::Zero();
    double time_s = 0.0;
};

struct PairOutcome {
    std::size_t source = 0, target = 0;  ///< Scan indices (input order).
    double match_score = 0.0;            ///< Best hypothesis's consensus score (0: none).
    std::size_t hypotheses = 0;          ///< Distinct pose hypotheses from matching.
    PairGlobalFigures global;
    bool verified = false;  ///< Global status success, within the session RMS gate.
    /// Global status success but its RMS exceeds the session RMS gate: not used.
    bool above_rms_gate = false;
    /// Refined hypotheses that passed the other tests but were rejected by the free-space
    /// check (look-alike poses).
    std::size_t free_space_rejections = 0;
    PairSlides slides;
    bool in_tree = false;  ///< An edge of the maximum spanning tree.
    double weight = 0.0;   ///< Tree weight: overlap / (1 + rms / target spacing).
    Pose T_target_source = Pose::Identity();  ///< Global result (when verified).
    PairFineFigures fine;
    bool linked = false;        ///< Gave a multi-view link.
    bool link_dropped = false;  ///< Dropped by the multi-view regression step.
};

/// Wall-clock seconds per stage.
struct ScanRegistrationTimings {
    double prepare_s = 0.0;
    double features_s = 0.0;    ///< Descriptors and patches of every scan.
    double matching_s = 0.0;    ///< Feature matching of every pair.
    double pairwise_s = 0.0;    ///< Refinement and verification of the pairs not skipped.
    double bridging_s = 0.0;    ///< Matching and verification of the bridging rounds.
    double pose_graph_s = 0.0;  ///< Spanning tree and initial poses.
    double fine_s = 0.0;        ///< Final fine registrations (links).
    double multiview_s = 0.0;
    double total_s = 0.0;
};

struct ScanRegistrationResult {
    std::vector<ScanOutcome> scans;  ///< Input order.
    /// Every pair, (1,0), (2,0), (2,1), ... (only the candidate pairs when pruned, then the
    /// bridging rounds' pairs).
    std::vector<PairOutcome> pairs;
    std::size_t reference_scan = 0;  ///< The world frame's scan (when any is placed).
    std::size_t placed_count = 0;
    std::size_t group_count = 0;  ///< Connected components among the loaded scans.
    std::size_t verified_pair_count = 0;
    /// The session RMS gate (metres; infinity when off or with too few scans) and the pairs
    /// it rejected.
    double session_rms_gate_m = 0.0;
    std::size_t gated_pair_count = 0;
    std::size_t bridge_pair_count = 0;  ///< Pairs added by the bridging rounds (at the end).
    std::size_t link_count = 0;
    std::size_t dropped_link_count = 0;
    /// Multi-view status of the largest group (converged when it has one scan).
    MultiviewStatus multiview_status = MultiviewStatus::kConverged;
    ScanRegistrationTimings timings;
    /// Out-of-core figures: clouds and site sets read back from the spill directory, and
    /// the first spill failure (empty when none; the affected pairs are not registered).
    std::size_t cloud_reloads = 0;
    std::string spill_error;
};

/// Progress messages ("global registration 3 of 45: ..."), for a log; may be empty.
using RegistrationProgress = std::function<void(std::string_view)>;

/// Registers `scans` (any order) and places as many as possible in a common frame. Never
/// throws on bad data: a scan that cannot be loaded or is empty is reported not placed.
ScanRegistrationResult register_scans(const std::vector<ScanInput>& scans,
                                      const ScanRegistrationConfig& config,
                                      const RegistrationProgress& progress);

/// Preparation of one loaded cloud: drops non-finite points; when the cloud has no normals
/// estimates them and orients them toward `sensor_origin_scan_m` (scan frame, metres) or,
/// without it, as seen from the estimated side (`orient_as_range_scan`); drops points left without
/// a finite unit normal; down-samples when `config.voxel_size_m` > 0. Returns the number of points
/// kept.
std::size_t prepare_scan(PointCloud& cloud, const std::optional<Eigen::Vector3d>& sensor_origin_m,
                         const ScanRegistrationConfig& config);

}  // namespace anascan
