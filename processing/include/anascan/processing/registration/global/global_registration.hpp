#pragma once
/// \file
/// Global pairwise registration (paper §4.2.1): no initial pose. Integral-invariant
/// features (integral_invariants.hpp, feature_patches.hpp) of both scans are matched:
/// candidate correspondences (same radius, side and level, similar descriptor and extent)
/// are pruned by pairwise geometric consistency (barycentre distances and normal angles
/// preserved), and a forward search (Atkinson et al. 2004) grows consistent sets from the
/// best seeds, refitting the rigid transform by weighted Kabsch at each step. The ranked
/// hypotheses are refined by `register_fine` and verified (RMS, overlap, normal deviation,
/// degeneracy). Only a verified pose is ever reported as success. See
/// docs/global-registration.md.
///
/// Thread safety: all functions are reentrant; TBB loops inside write one slot per item, so
/// results do not depend on the number of threads.

#include <cstddef>
#include <optional>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include "anascan/processing/core/pose.hpp"
#include "anascan/processing/evaluation/free_space.hpp"
#include "anascan/processing/features/feature_patches.hpp"
#include "anascan/processing/features/integral_invariants.hpp"
#include "anascan/processing/registration/fine/fine_registration.hpp"

namespace anascan {

/// Settings of feature matching (candidates, pruning, forward search).
struct FeatureMatchingConfig {
    /// Candidate when |V̄_s − V̄_t| ≤ max(descriptor_tolerance, descriptor_fraction ×
    /// |V̄_s − 1/2|).
    double descriptor_tolerance = 0.01;
    double descriptor_fraction = 0.3;
    double max_extent_ratio = 2.0;  ///< Largest principal extents differ by at most this.
    /// Distance tolerance (metres) between barycentres: base + fraction × the largest
    /// principal extent involved (partly visible patches move their barycentre).
    double distance_tolerance_m = 0.003;
    double distance_extent_fraction = 0.3;
    double max_normal_angle_deg = 20.0;    ///< Angle between normal pairs preserved within.
    std::size_t max_candidates = 1500;     ///< Keep the most similar candidates only.
    std::size_t seed_count = 40;           ///< Forward searches started (best-connected first).
    std::size_t seed_partners = 60;        ///< Second correspondences tried per seed.
    std::size_t min_inliers = 4;           ///< Smaller consistent sets are no hypothesis.
    std::size_t max_hypotheses = 30;       ///< Distinct poses returned, best first.
    double distinct_rotation_deg = 5.0;    ///< Hypotheses closer than this and ...
    double distinct_translation_m = 0.01;  ///< ... this are the same pose.
};

/// One candidate correspondence between a source and a target patch.
struct FeatureCorrespondence {
    std::size_t source_patch = 0;
    std::size_t target_patch = 0;
    double tolerance_m = 0.0;  ///< Allowed barycentre residual, metres.
};

/// A rigid transform supported by a consistent set of correspondences.
struct PoseHypothesis {
    Pose T_target_source = Pose::Identity();
    std::vector<FeatureCorrespondence> inliers;
    double score = 0.0;  ///< Consistency score: distinct inlier patches (higher is better).
    double rms_m = 0.0;  ///< RMS barycentre residual of the inliers, metres.
};

struct FeatureMatchingResult {
    std::size_t candidate_count = 0;         ///< Candidates after descriptor/extent tests.
    std::size_t consistent_count = 0;        ///< Candidates with at least one consistent partner.
    std::vector<PoseHypothesis> hypotheses;  ///< Distinct poses, best score first.
};

/// Candidates, pruning and forward search between the patches of two scans.
FeatureMatchingResult match_features(const FeaturePatchResult& source,
                                     const FeaturePatchResult& target,
                                     const FeatureMatchingConfig& config);

/// A direction known in both scans (e.g. "up": toward the sensors above a stone on the
/// ground). A pose is admissible when it turns `source_axis` to an angle with `target_axis`
/// within [min_angle_deg, max_angle_deg]: a stone that lies as before keeps its up (small
/// angles), one turned over has it turned down (large angles).
struct AxisConstraint {
    Eigen::Vector3d source_axis = Eigen::Vector3d::UnitZ();  ///< Source frame, any length.
    Eigen::Vector3d target_axis = Eigen::Vector3d::UnitZ();  ///< Target frame, any length.
    double min_angle_deg = 0.0;
    double max_angle_deg = 180.0;
    bool admits(const Eigen::Isometry3d& T_target_source) const;
};

/// Settings of `register_global`.
struct GlobalRegistrationConfig {
    /// Descriptor radii; all zero = `radii_for_object_size_m` of the larger scan diagonal.
    InvariantRadii radii_m{};
    /// Its radii_m are replaced by the above. Samples at r/6 (~110 per ball) rather than
    /// r/8 halve the descriptor time at no measured loss of reliability.
    IntegralInvariantConfig invariants{.sample_spacing_fraction = 1.0 / 6.0};
    FeaturePatchConfig patches{};
    FeatureMatchingConfig matching{};
    /// Refinement of each hypothesis; its first gate must cover the hypotheses' error.
    FineRegistrationConfig fine{.max_correspondence_distance_m = 0.015,
                                .min_correspondence_distance_m = 0.004,
                                .max_iterations = 40};
    /// Hypotheses are re-ranked by site overlap × consensus score; site overlap is the
    /// fraction of source sites that land within this many site spacings of a target site
    /// with a normal within 30°.
    double site_overlap_spacing_factor = 3.0;
    std::size_t max_refined = 6;  ///< Best re-ranked hypotheses refined and verified.
    /// Once one hypothesis is verified, the others are refined (for the ambiguity test) only
    /// while their ranking key is at least this fraction of the verified one's.
    double min_rank_ratio_after_verified = 0.3;
    /// Verification: RMS point-to-plane residual at most this many target sample spacings.
    double max_rms_spacing_factor = 1.0;
    double min_overlap_fraction = 0.25;      ///< Of the source samples (fine.overlap_distance).
    double max_normal_deviation_deg = 20.0;  ///< Mean source/target normal angle (overlap).
    /// Another verified pose (distinct, see matching) whose overlap reaches this fraction of
    /// the best one's makes the result ambiguous ...
    double ambiguity_overlap_ratio = 0.8;
    /// ... unless one of them fits clearly better: among the verified poses with such an
    /// overlap (contenders) the one of least RMS wins when every other contender's RMS is
    /// at least this multiple of it. A box seen from two nearby views fits at its true pose
    /// (0.2 mm on the simulated small block) and turned by 90° or 180° (0.8-0.9 mm); both
    /// pass the verification limit. 0: any second contender makes the pair ambiguous.
    double ambiguity_rms_ratio = 2.0;
    /// Inadmissible hypotheses are dropped before refinement and rejected after it.
    std::optional<AxisConstraint> axis_constraint;
    /// Free-space check of the poses that pass the tests above, when a scan's sensor
    /// position is known (`Viewpoints`): rejected when more than
    /// free_space.max_violation_fraction of one scan's points seen by the other's sensor lie
    /// in front of its surface. Look-alike poses of a box (turned by 90° or 180°) fit within
    /// a sample spacing but put the block's faces and the ground where the other sensor saw
    /// empty space.
    FreeSpaceConfig free_space{};
    /// Slide probes: when the chosen pose's fine registration leaves a weak direction (its
    /// degeneracy eigenvalue ratio is below this, though above fine.degeneracy_threshold),
    /// the pose is refined again from starts slid along that direction's translation by
    /// ±1..slide_probe_steps × fine.max_correspondence_distance_m (the reach of one
    /// refinement), and the results are decided as the other hypotheses: a slid pose that
    /// fits clearly better wins, one that fits alike makes the pair ambiguous. A block on
    /// the ground seen from two nearby views is fixed along its length only by an end face;
    /// a hypothesis 28 mm off along it refined to a pose still 28 mm off (0.21 mm RMS,
    /// eigenvalue ratio 0.004) because the end faces lay beyond the correspondence gate,
    /// while the true pose fits at 0.10 mm (docs/scan-registration.md "Slides"). Well
    /// constrained pairs (bunny: ~0.1) are not probed. 0: off.
    double slide_probe_max_eigenvalue_ratio = 0.02;
    int slide_probe_steps = 2;  ///< Probes on each side of the pose.
};

/// Sensor positions of the two scans of a pair, each in its own scan frame (metres), when
/// known exactly (where the scan was taken from, not a guess for orienting normals). Each
/// known one enables the free-space check of the other scan's points in its view.
struct Viewpoints {
    std::optional<Eigen::Vector3d> source_m;
    std::optional<Eigen::Vector3d> target_m;
};

enum class GlobalRegistrationStatus {
    kSuccess,             ///< One verified pose.
    kAmbiguous,           ///< Several distinct verified poses of similar quality.
    kNoConsensus,         ///< No consistent set of feature correspondences.
    kFailedVerification,  ///< Hypotheses found, none survived refinement and verification.
    kInvalidInput,        ///< Empty clouds, missing normals, bad config.
};

/// Short English name ("success", "ambiguous", ...), for logs and JSON.
std::string_view to_string(GlobalRegistrationStatus status);

/// One hypothesis as refined and verified.
struct HypothesisOutcome {
    PoseHypothesis hypothesis;    ///< Before refinement (inliers, score).
    double site_overlap = 0.0;    ///< Source sites near a target site, before refinement.
    FineRegistrationResult fine;  ///< After refinement (pose and figures).
    bool verified = false;
    std::string rejection;  ///< Why verification failed (empty when verified).
    /// Free-space check (passed the other tests, a viewpoint known): the larger violation
    /// fraction of the two directions checked.
    std::optional<double> free_space_violation_fraction;
    bool free_space_rejected = false;  ///< Rejected by the free-space check alone.
    /// Started from the chosen pose slid along its weakest direction (slide probe), by
    /// this many millimetres (signed, along GlobalRegistrationResult::slide_direction).
    std::optional<double> slide_start_mm;
};

/// Wall-clock seconds per stage.
struct GlobalRegistrationTiming {
    double invariants_s = 0.0;
    double patches_s = 0.0;
    double matching_s = 0.0;
    double refinement_s = 0.0;
    double total_s = 0.0;
};

struct GlobalRegistrationResult {
    GlobalRegistrationStatus status = GlobalRegistrationStatus::kInvalidInput;
    std::string message;
    /// The best verified pose (success or ambiguous); identity otherwise (not a result).
    Pose T_target_source = Pose::Identity();
    double rms_m = 0.0;  ///< Of the best verified pose (fine registration).
    double overlap_fraction = 0.0;
    double normal_deviation_deg = 0.0;
    std::size_t best_hypothesis = 0;  ///< Index into `hypotheses` when verified.
    InvariantRadii radii_m{};
    double target_spacing_m = 0.0;  ///< Median target sample spacing (verification scale).
    std::size_t source_patches = 0, target_patches = 0;
    FeatureMatchingResult matching;  ///< Candidate counts and the hypotheses before refinement.
    /// In the order tried (best site overlap × score first); hypotheses that started
    /// within the distinct-pose tolerance of an already verified pose are skipped.
    std::vector<HypothesisOutcome> hypotheses;
    std::size_t free_space_rejections = 0;  ///< Hypotheses rejected by the free-space check.
    std::size_t slide_probes = 0;  ///< Slide probes refined (see slide_probe_max_eigenvalue_ratio).
    /// The probed direction: translation of the chosen pose's weakest direction (target
    /// frame, unit; zero when not probed).
    Eigen::Vector3d slide_direction = Eigen::Vector3d::Zero();
    /// Ambiguous because a slid pose fits alike: the overlap does not fix the pose along
    /// slide_direction, by up to slide_m (the largest distance between such contenders, metres).
    bool slide_ambiguous = false;
    double slide_m = 0.0;
    GlobalRegistrationTiming timing;
};

/// What global registration needs of one scan, computed once and matched against many:
/// descriptors at the shared radii, patches at shared saliency levels, the sample spacing.
struct ScanFeatures {
    IntegralInvariantResult invariants;
    FeaturePatchResult patches;
    double spacing_m = 0.0;  ///< Median sample spacing (verification scale as a target).
};

/// The descriptor radii for registering `clouds` together: config.radii_m unless all zero,
/// else `radii_for_object_size_m` of the largest cloud diagonal (shared by all scans, so
/// their descriptors compare).
InvariantRadii registration_radii_m(std::span<const PointCloud* const> clouds,
                                    const GlobalRegistrationConfig& config);

/// The same from the largest local-bounds diagonal of the clouds (metres).
InvariantRadii registration_radii_m(double largest_diagonal_m,
                                    const GlobalRegistrationConfig& config);

/// Descriptors of one scan at `radii_m` (config.invariants with its radii replaced).
IntegralInvariantResult describe_scan(const PointCloud& cloud, const InvariantRadii& radii_m,
                                      const GlobalRegistrationConfig& config);

/// Patches of described scans at saliency levels pooled over all of them (so that every
/// pair cuts its regions at the same values). Invalid descriptors give no patches.
std::vector<ScanFeatures> scan_features(std::vector<IntegralInvariantResult> invariants,
                                        std::span<const double> spacings_m,
                                        const GlobalRegistrationConfig& config);

/// Registers `source` onto `target` from their precomputed features (same radii; see
/// `scan_features`): matching, refinement, verification. Otherwise as below.
GlobalRegistrationResult register_global(const PointCloud& source, const ScanFeatures& source_f,
                                         const PointCloud& target, const ScanFeatures& target_f,
                                         const GlobalRegistrationConfig& config,
                                         const Viewpoints& viewpoints = {});

/// Registers `source` onto `target` without an initial pose. Both clouds need unit normals
/// pointing out of the solid (e.g. toward the scanner). The returned `T_target_source`
/// maps source points (cloud frame, origin included) into the target frame. With
/// `viewpoints`, verification includes the free-space check (config.free_space).
GlobalRegistrationResult register_global(const PointCloud& source, const PointCloud& target,
                                         const GlobalRegistrationConfig& config,
                                         const Viewpoints& viewpoints = {});

}  // namespace anascan
