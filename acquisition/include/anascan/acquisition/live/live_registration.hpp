#pragma once
/// \file
/// On-site, acquisition-aware registration (DESIGN.md "On-site registration"): scans arrive one at
/// a time in capture order and are placed as they come.
///
/// For each new scan `add` keeps a reduced copy (non-finite points dropped, voxel
/// down-sampled, normals oriented toward the sensor, the ground plane removed: stone only)
/// and tries, cheapest first:
///  1. the constant-velocity motion prior (the operator walks around the stone in steps:
///     the step between the last two registered scans of the group, applied once more);
///  2. the previous scan's pose;
/// each refined by fine registration against the group's model (the registered scans whose
/// sensors stood nearest the hypothesis, merged) and verified as in batch registration (converged,
/// overlap, normals agree, RMS within the sample spacing, not degenerate). If neither
/// verifies: global registration from integral-invariant features against the registered
/// scans, most recent first, of every group (stone only, so a stone turned over still
/// matches itself), a verified pose near a prior taken, else one that several target scans
/// vote for; if that fails too the scan opens a new group. After the operator marks the
/// stone turned over, the cheap hypotheses are skipped until a scan is placed. See
/// docs/live-registration.md.
///
/// `refine` (background work, bounded per call) merges groups by the capture order (a scan
/// next to another group's scans is predicted there by the motion priors, run backwards
/// when they come after it), by global registration of whole groups under the stone's up,
/// or by votes of scan pairs; computes a few missing features, fine-registers
/// every new pair of overlapping scans of a group keeping the correspondences (multi-view
/// links) and solves each group's poses at once (`refine_multiview`, paper eq. 4); it
/// returns the poses that changed.
///
/// Frames: group g's frame is the frame of its first scan; group 0 is the first scan's.
/// When groups merge, the lower id survives and the other's poses are re-expressed in it.
///
/// Thread safety: not thread-safe; one thread (the registration worker) owns the object.
/// No I/O, no threads of its own (processing's TBB loops run inside).

#include <Eigen/Core>
#include <cstddef>
#include <cstdint>
#include <functional>
#include <memory>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "anascan/processing/cleaning/normals.hpp"
#include "anascan/processing/cleaning/plane_removal.hpp"
#include "anascan/processing/core/expected.hpp"
#include "anascan/processing/core/point_cloud.hpp"
#include "anascan/processing/core/pose.hpp"
#include "anascan/processing/evaluation/group_consistency.hpp"
#include "anascan/processing/registration/fine/fine_registration.hpp"
#include "anascan/processing/registration/global/global_registration.hpp"
#include "anascan/processing/registration/multiview/multiview_refinement.hpp"

namespace anascan::acquisition {

/// How a new scan is reduced to its stone-only copy.
struct LivePrepareConfig {
    /// Reduced copies are voxel down-sampled to this edge (metres): ~1.5-2 mm keeps a
    /// structured-light scan of ~300k points at ~30k points.
    double voxel_size_m = 0.002;
    NormalEstimationConfig normals{};  ///< On the reduced cloud.
    /// The ground: the dominant plane with the other points on the sensor's side of it.
    PlaneFitConfig ground{.distance_threshold_m = 0.003, .min_inlier_fraction = 0.05};
    /// Points within this distance (metres) of the ground plane, or below it, are dropped.
    double ground_band_m = 0.004;
    /// A plane is the ground when at least this fraction of the points off it lie on the
    /// sensor's side (a stone face seen from the front has the others behind it).
    double ground_sensor_side_fraction = 0.9;
    int ground_attempts = 3;            ///< Planes tried (each rejected one is set aside).
    std::size_t min_scan_points = 500;  ///< Fewer stone points: the scan is not usable.
};

/// The cheap hypotheses (motion priors, previous pose) and their fine registration against
/// the group's model.
struct LiveHypothesisConfig {
    /// Fine registration of a hypothesis against the model; the first gate must cover the
    /// error of a motion prior (a few centimetres when the operator's steps vary).
    FineRegistrationConfig fine{.max_correspondence_distance_m = 0.06,
                                .min_correspondence_distance_m = 0.003,
                                .max_iterations = 40,
                                .overlap_distance_m = 0.003};
    /// A cheap hypothesis is a prediction: its refined pose may differ from it by at most
    /// this rotation (degrees) and this displacement of the scan's centroid (metres), else
    /// the fine registration is taken for a wrong local minimum.
    double max_prior_correction_deg = 15.0;
    double max_prior_correction_m = 0.15;
    /// A larger correction, up to these, is taken when the refined pose fits like the
    /// session's accepted scans (once `LiveVerifyConfig::min_accepted_for_limits` were
    /// accepted): RMS and normal deviation at most `fitting_correction_factor` times their
    /// medians. On the demo session the operator's steps are 33-40°, and from the motion
    /// priors of the scans after the turn-over fine registration found, 28-37° away, the
    /// very pose global registration found (0.17-0.18 mm RMS); the one wrong minimum had
    /// 0.43 mm, 6.8°.
    double max_fitting_correction_deg = 45.0;
    double max_fitting_correction_m = 0.3;
    double fitting_correction_factor = 1.5;
    std::size_t model_scans = 5;  ///< Registered scans merged into the model of a hypothesis.
    /// A verified pose is probed by restarts shifted ± this (metres) along its weakest
    /// direction (an ornament band repeats every few centimetres: a start 3 cm off a slide
    /// of one period lies in the right basin); a restart whose overlap is larger by
    /// `slide_overlap_margin` replaces it. 0 = no probes.
    double slide_probe_m = 0.03;
    double slide_overlap_margin = 0.01;
    /// The first scan after the operator marked the stone turned over opens a new group at
    /// once: the other side's scans match it only by look-alike poses (on the demo session
    /// eight global attempts, ~6 s, decided nothing), and the whole-group merge joins the
    /// sides once the new one has a few scans. False: it tries global registration first.
    bool new_group_after_turn = true;
};

/// When a fine registration is accepted.
struct LiveVerifyConfig {
    /// RMS at most this many voxel sizes ...
    double max_rms_voxel_factor = 0.75;
    /// ... and, once `min_accepted_for_limits` scans were accepted, at most this multiple of
    /// the session's median accepted RMS (not below `min_rms_limit_m`): a scan slid along a
    /// weak direction keeps an RMS within the voxel but several times the session's noise ...
    double accepted_rms_median_factor = 2.5;
    double min_rms_limit_m = 0.0002;
    /// ... a normal deviation at most this multiple of the session's median accepted one
    /// (not below `min_normal_deviation_limit_deg`) ...
    double accepted_normal_median_factor = 2.0;
    double min_normal_deviation_limit_deg = 3.0;
    std::size_t min_accepted_for_limits = 3;
    /// ... and a degeneracy figure (smallest / largest eigenvalue) at least this (and at
    /// least the fine registration's degeneracy_threshold). 0: only the latter. Measured on
    /// the small block's structured-light tour, right alignments have 0.0016-0.016 (views of
    /// two faces at 30° steps are weakly constrained), so no fixed bound separates a slide.
    double min_degeneracy_ratio = 0.0;
    double min_overlap_fraction = 0.3;       ///< ... overlap of the new scan at least this ...
    double max_normal_deviation_deg = 20.0;  ///< ... and mean normal angle at most this.
};

/// Global registration of a new scan against registered scans.
struct LiveGlobalConfig {
    /// Features at radii fixed for the session (see `radii_m`). Its slide probes are off:
    /// the live registrar probes slides itself (`LiveHypothesisConfig::slide_probe_m`) with
    /// the session's model.
    GlobalRegistrationConfig registration{.slide_probe_max_eigenvalue_ratio = 0.0};
    /// Descriptor radii for the session; all zero = from the first usable scan's diagonal.
    InvariantRadii radii_m{};
    std::size_t max_targets = 8;  ///< Registered scans tried per global attempt.
    /// Once `min_links_for_rms_gate` links exist, a global hypothesis counts only with an RMS
    /// within this multiple of the links' median RMS: a near-symmetric stone (a box with
    /// different relief per face) matches itself turned by 90° or 180° at a few times the
    /// RMS of the right pose.
    double rms_median_factor = 2.5;
    std::size_t min_links_for_rms_gate = 5;
    /// A verified global pose (any hypothesis, also of an ambiguous result) within these of
    /// a motion prior or the previous pose is taken: the prior resolves the look-alikes.
    double max_prior_deg = 30.0;
    double max_prior_m = 0.3;
};

/// Without a prior, a global pose needs verified votes from at least `min_count` target
/// scans, `ratio` times more than any other pose's; votes agree within these.
struct LiveVoteConfig {
    std::size_t min_count = 2;
    double ratio = 2.0;
    double rotation_deg = 3.0;
    double displacement_m = 0.01;
};

/// Links for multi-view refinement (paper eq. 4).
struct LiveLinkConfig {
    /// Pairs of one group whose predicted overlap (feature sites) reaches this fraction are
    /// fine registered from their current poses.
    double min_overlap_fraction = 0.15;
    /// The links sample many points: along a weakly constrained direction (two faces in
    /// view) a link's error falls with the square root of its samples, and the chain of
    /// links around the stone adds them up (3000 samples: 0.6 mm at the far side of the
    /// demo session; 20 000: 0.17 mm; 60 000, about all of a reduced scan: 0.15-0.17 mm on
    /// two live captures against 0.16-0.22 mm, docs/live-registration.md).
    FineRegistrationConfig fine{.max_correspondence_distance_m = 0.006,
                                .min_correspondence_distance_m = 0.002,
                                .max_iterations = 30,
                                .sample_count = 60000,
                                .overlap_distance_m = 0.003,
                                .keep_correspondences = true};
    /// Correspondences a link keeps for the multi-view solve (`compress_link`: same optimum
    /// and stiffness as all of them, a tenth of the memory). 0 = all.
    std::size_t max_correspondences = 2000;
    /// Each scan is linked to at most this many earlier scans of its group per side (as the
    /// operator's turn-overs number them), those of largest forecast overlap: a round's fine
    /// registrations grow with the scans, not with their pairs (a scan overlaps its
    /// neighbours only; all pairs of the 50 scans of a stone took 18 minutes at the end of a
    /// capture on a loaded machine). 0 = every overlapping pair.
    std::size_t max_per_scan = 6;
    /// A tried pair is tried again when its scans' relative pose moved by more than these
    /// since (degrees, metres at the source's centroid): a scan corrected by the refinement
    /// gets links to its true neighbours, and links computed from a wrong pose are redone.
    double retry_deg = 0.05;
    double retry_m = 0.0005;
    /// Links whose overlap only fixes some directions (one face, a band of the sides: the
    /// fine registration reports them degenerate) are kept too: their fine registration
    /// moved only along the fixed directions, and in the multi-view solve they add stiffness
    /// only there. Across a turn-over every pair is of this kind (eigenvalue ratios 2e-5 to
    /// 6e-4 on the demo session); without them the second side hangs on the one rigid
    /// transform of the group merge.
    bool degenerate = true;
    /// A link needs an RMS within this many voxel sizes (looser than the verification:
    /// its correspondences reach farther).
    double max_rms_voxel_factor = 1.0;
    MultiviewRefinementConfig multiview{};  ///< fixed_scan_index is set per group.
};

/// Group merges in the background.
struct LiveMergeConfig {
    /// Merges by global registration of the whole groups' clouds, with the stone's up
    /// (each group's mean viewing direction) kept within `max_same_side_up_deg` on the same
    /// side and turned by at least 90° across a turn-over; tried again when one of the two
    /// groups has grown by half.
    bool whole_groups = true;
    std::size_t min_group_scans_for_up = 3;
    /// A whole-group match counts with an RMS up to this multiple of the session's gates
    /// (merged clouds of several scans fit looser than one pair) ...
    double whole_group_rms_factor = 1.5;
    /// ... and, when other poses verified too, an RMS at most this fraction of theirs.
    double whole_group_rms_ratio = 0.7;
    double max_same_side_up_deg = 30.0;
    /// With fewer scans in a group its up is one viewing direction: the bounds widen by this.
    double few_scans_up_slack_deg = 45.0;
    std::size_t max_attempts = 4;  ///< Global pair attempts per refine() for merges.
};

/// After each refinement every group's scans are checked against each other in their current
/// poses (processing's `check_group_consistency`: crossing normals, free space, overlap
/// angle, at thresholds from the reduced scans' own spacing and noise). A group merged in
/// since the last passing check that a disagreeing pair touches is taken out whole (with the
/// merges after it); then the scans whose removal restores agreement, one at a time. What
/// stays is split into the parts that agreeing overlapping pairs hold together.
struct LiveConsistencyConfig {
    bool enabled = true;
    /// The relief test on: a near-symmetric stone's look-alike fits its faces, not its
    /// relief (calibrated on the simulated structured-light head only; see Known limits).
    GroupConsistencyConfig check{.max_offset_noise_factor = 1.5};
    /// A group is checked again once a scan joined or left it, or a pose moved by more than
    /// these since its last check (degrees, metres at the scan's centroid).
    double recheck_deg = 0.05;
    double recheck_m = 0.0005;
};

/// Settings of a live registration session, by concern. Callers use designated initialisers.
struct LiveRegistrationConfig {
    LivePrepareConfig prepare{};
    LiveHypothesisConfig hypotheses{};
    LiveVerifyConfig verify{};
    LiveGlobalConfig global{};
    LiveVoteConfig votes{};
    LiveLinkConfig links{};
    LiveMergeConfig merges{};
    LiveConsistencyConfig consistency{};
    /// Scans whose features (for a later global registration) refine() computes per call.
    std::size_t max_features_per_refine = 2;
    /// Lengths raised to what the device's noise needs, measured on the session's first
    /// usable scan (voxel, ground band, gates, overlap distances, vote tolerances;
    /// docs/live-registration.md "Lengths from the device"). Off by default: with them a
    /// terrestrial scanner's stations join, but in the simulated tent 180° off (the room's
    /// symmetry), which no check sees while the reduced copies keep the tent.
    bool lengths_from_device = false;
};

/// One scan handed to the registrar.
struct LiveScanInput {
    std::int64_t seq = 0;  ///< Sequence number (capture order), unique.
    PointCloud cloud;      ///< In the scan frame, metres (normals optional: recomputed).
    /// Sensor position in the scan frame; orients normals and tells the ground's side.
    /// Absent: (0, 0, 0) (structured-light and ToF scans are in the sensor's frame).
    std::optional<Eigen::Vector3d> sensor_origin_scan_m;
    bool turned_over_before = false;  ///< The operator marked the stone turned over.
};

/// A hypothesis tried for a scan.
enum class LiveHypothesis {
    kMotionPrior,   ///< "motion-prior": constant velocity.
    kMotionPrior2,  ///< "motion-prior-2": double step (alternating elevations).
    kPreviousPose,  ///< "previous-pose".
    kGlobal,        ///< "global": against one target scan.
    kGlobalModel,   ///< "global-model": the chosen global pose refined against the model.
};
/// The name stored in a session's decision JSON (stable: stored sessions read it).
std::string_view to_string(LiveHypothesis hypothesis);

/// How `add` placed a scan.
enum class LiveMethod {
    kFirst,         ///< "first": the session's frame.
    kMotionPrior,   ///< "motion-prior" (also the double step).
    kPreviousPose,  ///< "previous-pose".
    kGlobal,        ///< "global".
    kNewGroup,      ///< "new-group": matches no earlier scan yet.
    kUnusable,      ///< "unusable": not registered (see the message).
};
/// The name stored in a session's decision JSON (stable: stored sessions read it).
std::string_view to_string(LiveMethod method);

/// One hypothesis tried for a scan.
struct LiveAttempt {
    LiveHypothesis method = LiveHypothesis::kGlobal;
    std::string status;  ///< "verified", or why not ("rms too large", "no_consensus", ...).
    std::int64_t target_seq = -1;  ///< Global: the target scan; else the latest model scan.
    int target_group = -1;
    double rms_m = 0.0;
    double overlap_fraction = 0.0;
    double time_s = 0.0;
};

/// What `add` decided for one scan, with its figures.
struct LiveDecision {
    std::int64_t seq = 0;
    bool registered = false;  ///< False: the scan is unusable (see message); no group.
    int group = -1;
    Pose T_group_scan = Pose::Identity();  ///< Scan frame into its group's frame.
    LiveMethod method = LiveMethod::kUnusable;
    double rms_m = 0.0;  ///< Of the accepted fine registration (0 for first/new-group).
    double overlap_fraction = 0.0;
    double normal_deviation_deg = 0.0;
    double degeneracy = 0.0;            ///< Smallest / largest eigenvalue ratio (1 = isotropic).
    double time_s = 0.0;                ///< Wall-clock time of add(), seconds.
    std::size_t reduced_points = 0;     ///< Stone points kept.
    std::vector<LiveAttempt> attempts;  ///< In the order tried.
    std::string message;                ///< Human-readable summary.
};

/// A pose that changed (refinement or group merge).
struct PoseUpdate {
    std::int64_t seq = 0;
    int group = -1;
    Pose T_group_scan = Pose::Identity();
};

/// A scan taken out of its group because it contradicts the group's other scans: it is out
/// of the model (no group, no links) until the operator registers it again.
struct LiveTakenOut {
    std::int64_t seq = 0;
    int group = -1;      ///< The group it was taken out of.
    std::string reason;  ///< Its worst disagreement, with figures.
    /// The pair test it failed there: "free space", "angle", "normals cross" or "surfaces
    /// apart" (group_consistency.hpp's `PairConsistency::reason`).
    std::string disagreement;
};

/// What `refine` did.
struct LiveRefineReport {
    std::size_t new_links = 0;
    std::size_t groups_refined = 0;
    std::size_t merges = 0;
    std::size_t merge_attempts = 0;  ///< Whole-group global registrations tried.
    /// The call stopped early because a new scan was waiting; the next call goes on.
    bool interrupted = false;
    double time_s = 0.0;
    std::size_t groups_checked = 0;       ///< Group consistency checks run.
    std::vector<LiveTakenOut> taken_out;  ///< Scans taken out and flagged by them.
    /// Scans moved to a new group after scans were taken out: nothing that stayed ties them to
    /// the rest of their old group any more (`group` is the old group; the new one is in the
    /// returned updates).
    std::vector<LiveTakenOut> split_off;
};

/// One registered scan of the model (for coverage): its reduced stone-only cloud.
struct LiveModelScan {
    std::int64_t seq = 0;
    int group = -1;
    const PointCloud* cloud = nullptr;  ///< Scan frame; valid until the next add/refine.
    Pose T_group_scan = Pose::Identity();
    Eigen::Vector3d sensor_origin_scan_m = Eigen::Vector3d::Zero();
};

/// The reduced, stone-only copy `add` keeps of a scan, in the scan's frame (down-sampled,
/// normals toward the sensor, the ground removed), or why the scan is not usable
/// (kInvalidArgument). For checks outside the registrar (another stone in view).
Expected<PointCloud> reduce_to_stone(LiveScanInput scan, const LiveRegistrationConfig& config = {});

/// The memory the registrar keeps, by part (bytes of the containers' capacities): what a
/// session grows by per scan.
struct LiveMemoryReport {
    std::size_t scans = 0;              ///< Entries kept (retired ones included).
    std::size_t cloud_bytes = 0;        ///< Reduced copies (positions, normals).
    std::size_t tree_bytes = 0;         ///< Their k-d trees.
    std::size_t feature_bytes = 0;      ///< Descriptors and patches kept for global registration.
    std::size_t features_kept = 0;      ///< Entries holding features.
    std::size_t links = 0;              ///< Multi-view links.
    std::size_t link_bytes = 0;         ///< Their correspondences.
    std::size_t model_cache_bytes = 0;  ///< The merged model of the last hypothesis, its tree.
    std::size_t total_bytes() const {
        return cloud_bytes + tree_bytes + feature_bytes + link_bytes + model_cache_bytes;
    }
};

/// The registrar: a single-threaded state machine (see the file comment).
class LiveRegistrar {
public:
    explicit LiveRegistrar(LiveRegistrationConfig config = {});
    ~LiveRegistrar();
    LiveRegistrar(LiveRegistrar&&) noexcept;
    LiveRegistrar& operator=(LiveRegistrar&&) noexcept;

    /// Registers one new scan; keeps its reduced copy, never the full cloud.
    LiveDecision add(LiveScanInput scan);
    /// Places a scan again (operator action): its old placement, links and figures are
    /// dropped and it is registered globally against the other registered scans (the
    /// operator's motion priors belong to the newest scan), else it opens a new group. Also
    /// for a scan not added before.
    LiveDecision reregister(LiveScanInput scan);
    /// Background work: links, multi-view refinement, group merges. Returns the changed
    /// poses (`last_refine_report` has the figures). `interrupt` is asked between links and
    /// between merge steps: once it says true the call returns what it has done, so a new
    /// scan waits for one link or merge attempt, not the whole round.
    std::vector<PoseUpdate> refine(const std::function<bool()>& interrupt = {});
    /// Why a scan was taken out of its group (see LiveTakenOut); none when it was not.
    std::optional<std::string> flagged(std::int64_t seq) const;
    /// Takes a scan out of the model (excluded = true) or back in; unknown seqs are ignored.
    void exclude(std::int64_t seq, bool excluded);

    /// The registered, not excluded scans.
    std::vector<LiveModelScan> model() const;
    /// Current pose and group of a scan (group -1 and nothing when unknown or unusable).
    std::optional<PoseUpdate> pose(std::int64_t seq) const;
    std::size_t group_count() const;  ///< Groups with at least one scan.
    const LiveRefineReport& last_refine_report() const;
    LiveMemoryReport memory() const;

private:
    struct State;
    std::unique_ptr<State> state_;
};

}  // namespace anascan::acquisition
