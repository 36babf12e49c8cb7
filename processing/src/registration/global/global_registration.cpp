// register_global: features → matching → refinement → verification (paper §4.2.1).
#include "anascan/processing/registration/global/global_registration.hpp"

#include <tbb/parallel_invoke.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <memory>
#include <numbers>
#include <optional>

#include "anascan/processing/core/stopwatch.hpp"
#include "anascan/processing/spatial/kdtree.hpp"
#include "registration/global/steps.hpp"

namespace anascan {
namespace {

using Clock = std::chrono::steady_clock;

std::string input_problem(const PointCloud& source, const PointCloud& target) {
    if (source.empty() || target.empty()) return "empty cloud";
    if (!source.has_normals() || !target.has_normals()) return "both clouds need normals";
    if (!source.attributes_consistent() || !target.attributes_consistent()) {
        return "inconsistent attributes";
    }
    return {};
}

bool all_finite(const PointCloud& cloud) {
    return std::all_of(cloud.positions.begin(), cloud.positions.end(),
                       [](const Eigen::Vector3f& p) { return p.allFinite(); });
}

/// Why a refined hypothesis is not acceptable; empty when it is.
std::string rejection(const FineRegistrationResult& fine, double spacing_m,
                      const GlobalRegistrationConfig& config) {
    if (fine.status != FineRegistrationStatus::kConverged &&
        fine.status != FineRegistrationStatus::kMaxIterations) {
        return "fine registration: " + std::string(to_string(fine.status));
    }
    if (fine.degeneracy.eigenvalue_ratio < config.fine.degeneracy_threshold) return "degenerate";
    if (config.axis_constraint && !config.axis_constraint->admits(fine.T_target_source)) {
        return "outside the axis constraint";
    }
    if (fine.rms_m > config.max_rms_spacing_factor * spacing_m) return "rms too large";
    if (fine.overlap_fraction < config.min_overlap_fraction) return "overlap too small";
    if (fine.normal_deviation_deg && *fine.normal_deviation_deg > config.max_normal_deviation_deg) {
        return "normal deviation too large";
    }
    return {};
}

bool features_valid(const ScanFeatures& features) {
    return features.invariants.status == IntegralInvariantStatus::kOk &&
           features.patches.status == FeaturePatchStatus::kOk;
}

/// Outcomes for every hypothesis, best site overlap × consensus score first (ties: matching
/// order).
std::vector<HypothesisOutcome> rank_by_site_overlap(const IntegralInvariantResult& source,
                                                    const IntegralInvariantResult& target,
                                                    const GlobalRegistrationConfig& config,
                                                    const FeatureMatchingResult& matching) {
    const KdTree target_sites(target.site_positions);
    const double distance_m = config.site_overlap_spacing_factor * target.site_spacing_m;
    std::vector<HypothesisOutcome> ranked;
    for (const PoseHypothesis& hypothesis : matching.hypotheses) {
        if (config.axis_constraint && !config.axis_constraint->admits(hypothesis.T_target_source))
            continue;
        HypothesisOutcome outcome;
        outcome.hypothesis = hypothesis;
        outcome.site_overlap = detail::site_overlap_fraction(
            source, target, target_sites, hypothesis.T_target_source, distance_m);
        ranked.push_back(std::move(outcome));
    }
    // Site overlap alone cannot tell poses that slide along flat parts apart; the feature
    // consensus alone favours repeated features: rank by their product.
    std::stable_sort(ranked.begin(), ranked.end(), [](const auto& a, const auto& b) {
        return a.site_overlap * a.hypothesis.score > b.site_overlap * b.hypothesis.score;
    });
    return ranked;
}

bool distinct(const Pose& a, const Pose& b, const FeatureMatchingConfig& config) {
    const PoseDifference d = pose_difference(a, b);
    return d.rotation_deg >= config.distinct_rotation_deg ||
           d.translation_m >= config.distinct_translation_m;
}

/// True when `T` starts near a pose that already refined and verified.
bool near_verified(const std::vector<HypothesisOutcome>& done, const Pose& T,
                   const FeatureMatchingConfig& config) {
    return std::any_of(done.begin(), done.end(), [&](const HypothesisOutcome& h) {
        return h.verified && !distinct(h.fine.T_target_source, T, config);
    });
}

/// The larger free-space violation fraction of the directions whose viewer's sensor is
/// known (source points in the target's view, target points in the source's); empty when
/// neither is known or too few points fall in a view.
std::optional<double> free_space_fraction(const detail::DescribedScan& source,
                                          const detail::DescribedScan& target, const Pose& T,
                                          const FreeSpaceConfig& config) {
    std::optional<double> worst;
    const auto add = [&](const FreeSpaceResult& r) {
        if (r.valid && r.in_view >= config.min_points_in_view)
            worst = std::max(worst.value_or(0.0), r.violation_fraction);
    };
    if (target.viewpoint_m) {
        add(check_free_space(target.cloud, *target.viewpoint_m, target.features.spacing_m,
                             source.cloud, T, config));
    }
    if (source.viewpoint_m) {
        add(check_free_space(source.cloud, *source.viewpoint_m, source.features.spacing_m,
                             target.cloud, T.inverse(), config));
    }
    return worst;
}

/// Rejects a hypothesis that passed the other tests when it puts points in free space.
void verify_free_space(const detail::DescribedScan& source, const detail::DescribedScan& target,
                       const FreeSpaceConfig& config, HypothesisOutcome& outcome) {
    if (!outcome.rejection.empty()) return;
    outcome.free_space_violation_fraction =
        free_space_fraction(source, target, outcome.fine.T_target_source, config);
    const double fraction = outcome.free_space_violation_fraction.value_or(0.0);
    if (fraction <= config.max_violation_fraction) return;
    outcome.free_space_rejected = true;
    outcome.rejection = "free space: " + std::to_string(static_cast<int>(fraction * 100.0 + 0.5)) +
                        "% of the points seen by the other sensor lie where it saw empty space";
}

/// Refines `outcome` from `T_initial` and verifies it (the tests, then free space).
void refine_one(const detail::DescribedScan& source, const detail::DescribedScan& target,
                const KdTree* tree, const Pose& T_initial, const GlobalRegistrationConfig& config,
                HypothesisOutcome& outcome, GlobalRegistrationResult& result) {
    outcome.fine = tree ? register_fine(source.cloud, target.cloud, *tree, T_initial, config.fine)
                        : register_fine(source.cloud, target.cloud, T_initial, config.fine);
    outcome.rejection = rejection(outcome.fine, result.target_spacing_m, config);
    verify_free_space(source, target, config.free_space, outcome);
    result.free_space_rejections += outcome.free_space_rejected;
    outcome.verified = outcome.rejection.empty();
}

void refine_hypotheses(const detail::DescribedScan& source, const detail::DescribedScan& target,
                       const KdTree* tree, std::vector<HypothesisOutcome> ranked,
                       const GlobalRegistrationConfig& config, GlobalRegistrationResult& result) {
    double verified_key = 0.0;  // Ranking key of the first verified hypothesis.
    for (HypothesisOutcome& outcome : ranked) {
        if (result.hypotheses.size() >= config.max_refined) break;
        const double key = outcome.site_overlap * outcome.hypothesis.score;
        if (key < config.min_rank_ratio_after_verified * verified_key) break;
        const Pose T_initial = outcome.hypothesis.T_target_source;
        if (near_verified(result.hypotheses, T_initial, config.matching)) continue;
        refine_one(source, target, tree, T_initial, config, outcome, result);
        if (outcome.verified && verified_key == 0.0) verified_key = key;
        result.hypotheses.push_back(std::move(outcome));
    }
}

/// Slide probes of the chosen pose (see slide_probe_max_eigenvalue_ratio): refines it again
/// from starts slid along the translation of its weakest direction. Returns whether any
/// probe was refined.
bool probe_slides(const detail::DescribedScan& source, const detail::DescribedScan& target,
                  const KdTree* tree, const GlobalRegistrationConfig& config,
                  GlobalRegistrationResult& result) {
    if (result.status != GlobalRegistrationStatus::kSuccess) return false;
    const HypothesisOutcome chosen = result.hypotheses[result.best_hypothesis];
    const DegeneracyFigure& weak = chosen.fine.degeneracy;
    const Eigen::Vector3d translation = weak.weakest_direction.tail<3>();
    // A weak direction that is mostly a rotation (a cylinder's axis) is not a slide.
    if (weak.eigenvalue_ratio >= config.slide_probe_max_eigenvalue_ratio ||
        translation.norm() < 0.5)
        return false;
    result.slide_direction = translation.normalized();
    const double step_m = config.fine.max_correspondence_distance_m;
    // Each probe runs even when it starts near a verified pose: a refinement still creeping
    // along the slide ends short of the minimum (max_iterations).
    for (int k = -config.slide_probe_steps; k <= config.slide_probe_steps; ++k) {
        if (k == 0) continue;
        const Eigen::Vector3d offset_m = k * step_m * result.slide_direction;
        const Pose start = Eigen::Translation3d(offset_m) * chosen.fine.T_target_source;
        HypothesisOutcome probe{.hypothesis = chosen.hypothesis,
                                .site_overlap = chosen.site_overlap,
                                .slide_start_mm = k * step_m * 1e3};
        refine_one(source, target, tree, start, config, probe, result);
        result.hypotheses.push_back(std::move(probe));
        ++result.slide_probes;
    }
    return result.slide_probes > 0;
}

/// Verified poses whose overlap reaches ambiguity_overlap_ratio of the largest verified one.
std::vector<bool> contenders(const GlobalRegistrationConfig& config,
                             const std::vector<HypothesisOutcome>& hypotheses) {
    double max_overlap = 0.0;
    for (const HypothesisOutcome& h : hypotheses) {
        if (h.verified) max_overlap = std::max(max_overlap, h.fine.overlap_fraction);
    }
    std::vector<bool> out;
    for (const HypothesisOutcome& h : hypotheses) {
        out.push_back(h.verified &&
                      h.fine.overlap_fraction >= config.ambiguity_overlap_ratio * max_overlap);
    }
    return out;
}

/// The contender of least RMS; success unless a distinct contender comes close
/// in overlap without fitting clearly worse.
void decide(const GlobalRegistrationConfig& config, GlobalRegistrationResult& result) {
    const std::vector<bool> contender = contenders(config, result.hypotheses);
    std::optional<std::size_t> best;  // The contender of least RMS.
    for (std::size_t i = 0; i < contender.size(); ++i) {
        if (contender[i] &&
            (!best || result.hypotheses[i].fine.rms_m < result.hypotheses[*best].fine.rms_m))
            best = i;
    }
    if (!best) {
        result.status = GlobalRegistrationStatus::kFailedVerification;
        result.message = "no hypothesis survived refinement and verification";
        return;
    }
    const FineRegistrationResult& fine = result.hypotheses[*best].fine;
    result.best_hypothesis = *best;
    result.T_target_source = fine.T_target_source;
    result.rms_m = fine.rms_m;
    result.overlap_fraction = fine.overlap_fraction;
    result.normal_deviation_deg = fine.normal_deviation_deg.value_or(0.0);
    result.status = GlobalRegistrationStatus::kSuccess;
    for (std::size_t i = 0; i < contender.size(); ++i) {
        const HypothesisOutcome& h = result.hypotheses[i];
        const bool clearly_worse = config.ambiguity_rms_ratio > 0.0 &&
                                   h.fine.rms_m >= config.ambiguity_rms_ratio * fine.rms_m;
        // A slide probe still moving when its iterations ran out is on its way along the
        // slide, not at a second minimum.
        const bool moving =
            h.slide_start_mm && h.fine.status == FineRegistrationStatus::kMaxIterations;
        if (contender[i] && !clearly_worse && !moving &&
            distinct(h.fine.T_target_source, fine.T_target_source, config.matching)) {
            result.status = GlobalRegistrationStatus::kAmbiguous;
            result.message = "several distinct verified poses";
            if (h.slide_start_mm || result.hypotheses[*best].slide_start_mm) {
                result.slide_ambiguous = true;
                result.slide_m = std::max(
                    result.slide_m,
                    pose_difference(h.fine.T_target_source, fine.T_target_source).translation_m);
            }
        }
    }
    if (result.slide_ambiguous) {
        result.message = "poses slid by up to " +
                         std::to_string(static_cast<int>(result.slide_m * 1e3 + 0.5)) +
                         " mm along the weakest direction fit alike: the overlap does not fix "
                         "the pose along it";
    }
}

}  // namespace

bool AxisConstraint::admits(const Eigen::Isometry3d& T_target_source) const {
    const Eigen::Vector3d turned = (T_target_source.linear() * source_axis).normalized();
    const double c = std::clamp(turned.dot(target_axis.normalized()), -1.0, 1.0);
    const double angle_deg = std::acos(c) * 180.0 / std::numbers::pi;
    return angle_deg >= min_angle_deg && angle_deg <= max_angle_deg;
}

namespace detail {

/// Fraction of source sites that land near a target site with a similar normal (30°).
double site_overlap_fraction(const IntegralInvariantResult& source,
                             const IntegralInvariantResult& target, const KdTree& target_sites,
                             const Pose& T_target_source, double distance_m) {
    if (source.site_positions.empty()) return 0.0;
    const Eigen::Isometry3f T_local = (Eigen::Translation3d(-target.origin_m) * T_target_source *
                                       Eigen::Translation3d(source.origin_m))
                                          .cast<float>();
    const float distance_sq = static_cast<float>(distance_m * distance_m);
    std::size_t near = 0;
    Neighbor nearest;
    for (std::size_t i = 0; i < source.site_positions.size(); ++i) {
        if (!target_sites.nearest(T_local * source.site_positions[i], nearest)) continue;
        const Eigen::Vector3f n = T_local.linear() * source.site_normals[i];
        near += nearest.distance_sq_m2 <= distance_sq &&
                n.dot(target.site_normals[nearest.index]) >= 0.866f;
    }
    return static_cast<double>(near) / static_cast<double>(source.site_positions.size());
}

GlobalRegistrationResult refine_and_verify(const DescribedScan& source, const DescribedScan& target,
                                           FeatureMatchingResult matching,
                                           const GlobalRegistrationConfig& config) {
    const Clock::time_point start = Clock::now();
    GlobalRegistrationResult result;
    result.message = input_problem(source.cloud, target.cloud);
    if (result.message.empty() &&
        (!features_valid(source.features) || !features_valid(target.features))) {
        result.message = "invalid descriptors";
    }
    if (!result.message.empty()) return result;
    result.radii_m = target.features.invariants.radii_m;
    result.target_spacing_m = target.features.spacing_m;
    result.source_patches = source.features.patches.patches.size();
    result.target_patches = target.features.patches.patches.size();
    result.matching = std::move(matching);
    if (result.matching.hypotheses.empty()) {
        result.status = GlobalRegistrationStatus::kNoConsensus;
        result.message = "no consistent set of feature correspondences";
    } else {
        std::unique_ptr<KdTree> tree;
        if (all_finite(target.cloud)) tree = std::make_unique<KdTree>(target.cloud.positions);
        refine_hypotheses(source, target, tree.get(),
                          rank_by_site_overlap(source.features.invariants,
                                               target.features.invariants, config, result.matching),
                          config, result);
        decide(config, result);
        if (probe_slides(source, target, tree.get(), config, result)) decide(config, result);
    }
    result.timing.refinement_s = seconds_since(start);
    result.timing.total_s = result.timing.refinement_s;
    return result;
}

}  // namespace detail

std::string_view to_string(GlobalRegistrationStatus status) {
    switch (status) {
        case GlobalRegistrationStatus::kSuccess:
            return "success";
        case GlobalRegistrationStatus::kAmbiguous:
            return "ambiguous";
        case GlobalRegistrationStatus::kNoConsensus:
            return "no_consensus";
        case GlobalRegistrationStatus::kFailedVerification:
            return "failed_verification";
        case GlobalRegistrationStatus::kInvalidInput:
            return "invalid_input";
    }
    return "unknown";
}

GlobalRegistrationResult register_global(const PointCloud& source, const ScanFeatures& source_f,
                                         const PointCloud& target, const ScanFeatures& target_f,
                                         const GlobalRegistrationConfig& config,
                                         const Viewpoints& viewpoints) {
    const Clock::time_point start = Clock::now();
    FeatureMatchingResult matching;
    if (features_valid(source_f) && features_valid(target_f)) {
        matching = match_features(source_f.patches, target_f.patches, config.matching);
    }
    const double matching_s = seconds_since(start);
    GlobalRegistrationResult result = detail::refine_and_verify(
        {source, source_f, viewpoints.source_m}, {target, target_f, viewpoints.target_m},
        std::move(matching), config);
    result.timing.matching_s = matching_s;
    result.timing.total_s = seconds_since(start);
    return result;
}

GlobalRegistrationResult register_global(const PointCloud& source, const PointCloud& target,
                                         const GlobalRegistrationConfig& config,
                                         const Viewpoints& viewpoints) {
    const Clock::time_point start = Clock::now();
    if (const std::string problem = input_problem(source, target); !problem.empty()) {
        GlobalRegistrationResult result;
        result.message = problem;
        return result;
    }
    const PointCloud* const both[] = {&source, &target};
    const InvariantRadii radii_m = registration_radii_m(both, config);
    std::vector<IntegralInvariantResult> invariants(2);
    tbb::parallel_invoke([&] { invariants[0] = describe_scan(source, radii_m, config); },
                         [&] { invariants[1] = describe_scan(target, radii_m, config); });
    const double invariants_s = seconds_since(start);
    const Clock::time_point patches_start = Clock::now();
    const double spacings_m[] = {median_sample_spacing_m(source), median_sample_spacing_m(target)};
    const std::vector<ScanFeatures> features =
        scan_features(std::move(invariants), spacings_m, config);
    const double patches_s = seconds_since(patches_start);
    GlobalRegistrationResult result =
        register_global(source, features[0], target, features[1], config, viewpoints);
    result.radii_m = radii_m;
    result.timing.invariants_s = invariants_s;
    result.timing.patches_s = patches_s;
    result.timing.total_s = seconds_since(start);
    return result;
}

}  // namespace anascan
