#include "anascan/processing/registration/fine/fine_registration.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <string>

#include "registration/fine/steps.hpp"

namespace anascan {

std::string_view to_string(FineRegistrationStatus status) {
    switch (status) {
        case FineRegistrationStatus::kConverged:
            return "converged";
        case FineRegistrationStatus::kMaxIterations:
            return "max_iterations";
        case FineRegistrationStatus::kDegenerate:
            return "degenerate";
        case FineRegistrationStatus::kInsufficientOverlap:
            return "insufficient_overlap";
        case FineRegistrationStatus::kInvalidInput:
            return "invalid_input";
    }
    return "unknown";
}

namespace {

using fine_detail::Accumulation;
using fine_detail::Match;
using fine_detail::Samples;
using fine_detail::TargetView;
using Clock = std::chrono::steady_clock;

// ---- Input checks (never throw, never a silent identity) -------------------------------

bool usable_target_point(const PointCloud& target, std::size_t i) {
    return target.positions[i].allFinite() && target.normals[i].allFinite();
}

std::string validate_config(const FineRegistrationConfig& c) {
    const bool ok = c.max_correspondence_distance_m > 0.0 &&
                    c.min_correspondence_distance_m > 0.0 && c.gate_shrink_factor > 0.0 &&
                    c.max_iterations >= 1 && c.max_polish_iterations >= 0 && c.sample_count >= 6 &&
                    c.robust_width_fraction > 0.0 && c.rotation_tolerance_rad >= 0.0 &&
                    c.translation_tolerance_m >= 0.0 && c.degeneracy_threshold >= 0.0 &&
                    c.overlap_distance_m > 0.0;
    return ok ? std::string()
              : "fine registration: a config value is out of range (distances, "
                "widths and factors must be > 0, max_iterations >= 1, "
                "sample_count >= 6)";
}

std::string validate_clouds(const PointCloud& source, const PointCloud& target) {
    if (source.empty()) return "fine registration: the source cloud is empty";
    if (target.empty()) return "fine registration: the target cloud is empty";
    if (!source.attributes_consistent()) return "source cloud: " + describe_inconsistency(source);
    if (!target.attributes_consistent()) return "target cloud: " + describe_inconsistency(target);
    if (!target.has_normals()) {
        return "fine registration: the target cloud has no normals (point-to-plane needs "
               "them; estimate normals first)";
    }
    for (std::size_t i = 0; i < target.size(); ++i) {
        if (usable_target_point(target, i)) return {};
    }
    return "fine registration: no target point has a finite position and normal";
}

std::string validate(const PointCloud& source, const PointCloud& target, const Pose& T_initial,
                     const FineRegistrationConfig& config) {
    if (!T_initial.matrix().allFinite()) return "fine registration: the initial pose is not finite";
    std::string message = validate_config(config);
    return message.empty() ? validate_clouds(source, target) : message;
}

FineRegistrationResult invalid_input(std::string message, const Pose& T_initial,
                                     Clock::time_point start) {
    FineRegistrationResult result;
    result.status = FineRegistrationStatus::kInvalidInput;
    result.message = std::move(message);
    result.T_target_source = T_initial;
    result.time_s = std::chrono::duration<double>(Clock::now() - start).count();
    return result;
}

// ---- Frames: the loop works in the clouds' local float frames --------------------------

Pose to_local(const Pose& T_target_source, const PointCloud& source, const PointCloud& target) {
    return Eigen::Translation3d(-target.origin_m) * T_target_source *
           Eigen::Translation3d(source.origin_m);
}

Pose from_local(const Pose& T_local, const PointCloud& source, const PointCloud& target) {
    return Eigen::Translation3d(target.origin_m) * T_local * Eigen::Translation3d(-source.origin_m);
}

// ---- Stopping predicates ---------------------------------------------------------------

/// The step rotated by less than the rotation tolerance and moved the samples' centroid
/// by less than the translation tolerance.
bool converged_by_increment(const Pose& step, const Eigen::Vector3d& centroid_m,
                            const FineRegistrationConfig& config) {
    const double angle_rad = Eigen::AngleAxisd(step.linear()).angle();
    const double shift_m = (step * centroid_m - centroid_m).norm();
    return angle_rad < config.rotation_tolerance_rad && shift_m < config.translation_tolerance_m;
}

bool reached_max_iterations(int iterations, int max_iterations) {
    return iterations >= max_iterations;
}

bool lacks_correspondences_count(std::size_t inliers, const FineRegistrationConfig& config) {
    return inliers < std::max<std::size_t>(config.min_correspondences, 6);
}

bool lacks_correspondences(const Accumulation& sums, const FineRegistrationConfig& config) {
    return lacks_correspondences_count(sums.inliers, config);
}

// ---- The iteration (eq. 2, then the helical motion) ------------------------------------

struct Workspace {
    std::vector<Match> matches;
    std::vector<Accumulation> chunk_sums;
};

// The gate follows the alignment: factor × RMS point distance, never growing, floored.
double shrunk_gate(double gate_m, const Accumulation& sums, const FineRegistrationConfig& config) {
    const double rms = std::sqrt(sums.point_distance_sq_sum / static_cast<double>(sums.inliers));
    return std::max(config.min_correspondence_distance_m,
                    std::min(gate_m, config.gate_shrink_factor * rms));
}

struct IterationOutcome {
    FineRegistrationStatus status = FineRegistrationStatus::kMaxIterations;
    int iterations = 0;
    Pose T_local = Pose::Identity();
    double gate_m = 0.0;
};

// Iterates from `start` until converged, out of correspondences or `max_iterations` steps.
IterationOutcome iterate(const Samples& samples, const TargetView& target,
                         const IterationOutcome& start, int max_iterations, bool symmetric,
                         const FineRegistrationConfig& config, Workspace& ws) {
    IterationOutcome out{FineRegistrationStatus::kMaxIterations, 0, start.T_local, start.gate_m};
    while (!reached_max_iterations(out.iterations, max_iterations)) {
        const Accumulation sums = fine_detail::match_and_accumulate(
            samples, target, out.T_local,
            fine_detail::match_settings(config, out.gate_m, symmetric), ws.matches, ws.chunk_sums);
        if (lacks_correspondences(sums, config)) {
            out.status = FineRegistrationStatus::kInsufficientOverlap;
            return out;
        }
        const Eigen::Vector3d centroid_m = out.T_local * samples.centroid_m;
        const DegeneracyFigure degeneracy =
            fine_detail::measure_degeneracy(sums.H, samples.length_m);
        const Pose step = helical_motion(fine_detail::solve_step(
            sums, degeneracy, config.degeneracy_threshold, samples.length_m, centroid_m));
        out.T_local = step * out.T_local;
        ++out.iterations;
        out.gate_m = shrunk_gate(out.gate_m, sums, config);
        if (converged_by_increment(step, centroid_m, config)) {
            out.status = FineRegistrationStatus::kConverged;
            return out;
        }
    }
    return out;
}

struct Refinement {
    IterationOutcome outcome;
    int polish_iterations = 0;
    bool polished = false;
};

// The iteration with the target's normals, then (see `symmetric_polish`) the symmetric one.
Refinement refine(const Samples& samples, const TargetView& target, const Pose& T_initial,
                  const FineRegistrationConfig& config, Workspace& ws) {
    const IterationOutcome start{FineRegistrationStatus::kMaxIterations, 0, T_initial,
                                 config.max_correspondence_distance_m};
    Refinement r{iterate(samples, target, start, config.max_iterations, false, config, ws)};
    const bool polish = config.symmetric_polish && config.max_polish_iterations > 0 &&
                        !samples.normals.empty() &&
                        r.outcome.status == FineRegistrationStatus::kConverged;
    if (!polish) return r;
    const IterationOutcome polished =
        iterate(samples, target, r.outcome, config.max_polish_iterations, true, config, ws);
    r.polish_iterations = polished.iterations;
    r.outcome.iterations += polished.iterations;
    if (polished.status != FineRegistrationStatus::kConverged) return r;
    r.polished = true;
    r.outcome.T_local = polished.T_local;
    r.outcome.gate_m = polished.gate_m;
    return r;
}

// ---- Status of the whole call -----------------------------------------------------------

void set_status(const IterationOutcome& outcome, const FineRegistrationConfig& config,
                FineRegistrationResult& result) {
    const bool too_little = result.overlap_fraction < config.min_overlap_fraction ||
                            lacks_correspondences_count(result.inlier_count, config);
    if (outcome.status == FineRegistrationStatus::kInsufficientOverlap || too_little) {
        result.status = FineRegistrationStatus::kInsufficientOverlap;
        result.message = "insufficient overlap: " + std::to_string(result.inlier_count) +
                         " correspondences, overlap fraction " +
                         std::to_string(result.overlap_fraction);
    } else if (result.degeneracy.eigenvalue_ratio < config.degeneracy_threshold) {
        result.status = FineRegistrationStatus::kDegenerate;
        result.message = "degenerate constraint (the surfaces can slide): eigenvalue ratio " +
                         std::to_string(result.degeneracy.eigenvalue_ratio) + " below " +
                         std::to_string(config.degeneracy_threshold);
    } else if (outcome.status == FineRegistrationStatus::kMaxIterations) {
        result.status = FineRegistrationStatus::kMaxIterations;
        result.message = "still moving after " + std::to_string(outcome.iterations) + " iterations";
    } else {
        result.status = FineRegistrationStatus::kConverged;
    }
}

FineRegistrationResult run(const PointCloud& source, const PointCloud& target, const KdTree& tree,
                           const Pose& T_initial, const FineRegistrationConfig& config) {
    const Samples samples = fine_detail::sample_spread(source, config.sample_count);
    if (samples.points.size() < 6) {
        return invalid_input("fine registration: the source has fewer than 6 finite points",
                             T_initial, Clock::now());
    }
    const TargetView view{target.positions, target.normals, &tree};
    Workspace ws{std::vector<Match>(samples.points.size()), {}};
    const Refinement refined =
        refine(samples, view, to_local(T_initial, source, target), config, ws);
    const IterationOutcome& outcome = refined.outcome;
    FineRegistrationResult result;
    result.T_target_source = from_local(outcome.T_local, source, target);
    result.iterations = outcome.iterations;
    result.polish_iterations = refined.polish_iterations;
    result.polished = refined.polished;
    result.sample_count = samples.points.size();
    fine_detail::rate_final_pose(
        {samples, view, outcome.T_local, outcome.gate_m, source.origin_m, target.origin_m}, config,
        result);
    set_status(outcome, config, result);
    return result;
}

// The target restricted to points with a finite position and normal (a copy, made only
// when the target has unusable points, so that the k-d tree never sees a NaN).
PointCloud usable_target(const PointCloud& target) {
    std::vector<std::size_t> keep;
    keep.reserve(target.size());
    for (std::size_t i = 0; i < target.size(); ++i) {
        if (usable_target_point(target, i)) keep.push_back(i);
    }
    return select(target, keep);
}

bool all_usable(const PointCloud& target) {
    for (std::size_t i = 0; i < target.size(); ++i) {
        if (!usable_target_point(target, i)) return false;
    }
    return true;
}

double seconds_since(Clock::time_point start) {
    return std::chrono::duration<double>(Clock::now() - start).count();
}

}  // namespace

FineRegistrationResult register_fine(const PointCloud& source, const PointCloud& target,
                                     const Pose& T_target_source_initial,
                                     const FineRegistrationConfig& config) {
    const Clock::time_point start = Clock::now();
    std::string message = validate(source, target, T_target_source_initial, config);
    if (!message.empty()) return invalid_input(std::move(message), T_target_source_initial, start);
    FineRegistrationResult result;
    if (all_usable(target)) {
        const KdTree tree(target.positions);
        result = run(source, target, tree, T_target_source_initial, config);
    } else {
        const PointCloud usable = usable_target(target);
        const KdTree tree(usable.positions);
        result = run(source, usable, tree, T_target_source_initial, config);
    }
    result.time_s = seconds_since(start);
    return result;
}

FineRegistrationResult register_fine(const PointCloud& source, const PointCloud& target,
                                     const KdTree& target_tree, const Pose& T_target_source_initial,
                                     const FineRegistrationConfig& config) {
    const Clock::time_point start = Clock::now();
    std::string message = validate(source, target, T_target_source_initial, config);
    if (message.empty() && target_tree.size() != target.size()) {
        message = "fine registration: the target tree indexes " +
                  std::to_string(target_tree.size()) + " points, the target has " +
                  std::to_string(target.size());
    }
    if (!message.empty()) return invalid_input(std::move(message), T_target_source_initial, start);
    FineRegistrationResult result =
        run(source, target, target_tree, T_target_source_initial, config);
    result.time_s = seconds_since(start);
    return result;
}

}  // namespace anascan
