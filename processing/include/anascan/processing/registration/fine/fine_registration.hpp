#pragma once
/// \file
/// Fine pairwise registration (paper §4.2.2): point-to-plane ICP with the linear velocity
/// field v(x) = c̄ + c × x (eq. 2, with r_i the target normal) and the exact helical motion
/// of (c, c̄) as the update. Reports the quality figures that rate a pair (RMS distance,
/// overlap, normal deviation) and whether the constraint is degenerate (the surfaces can
/// slide along each other), and keeps the final correspondences for multi-view
/// registration (eq. 4) on request. See docs/fine-registration.md.
///
/// Thread safety: `register_fine` is reentrant; it runs TBB loops internally and its
/// results do not depend on the number of threads.

#include <Eigen/Core>
#include <cstddef>
#include <cstdint>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "anascan/processing/core/point_cloud.hpp"
#include "anascan/processing/core/pose.hpp"
#include "anascan/processing/spatial/kdtree.hpp"

namespace anascan {

/// How residuals are weighted (iteratively reweighted least squares).
enum class RobustKernel {
    kNone,   ///< Plain least squares (every correspondence within the gate counts fully).
    kHuber,  ///< Weight min(1, k / |r|): outliers count linearly.
    kTukey,  ///< Weight (1 - (r/k)²)² for |r| < k, else 0: outliers are ignored.
};

/// Settings of one fine registration. Callers use designated initialisers.
struct FineRegistrationConfig {
    /// Correspondences farther apart (point to point, metres) are ignored in the first
    /// iteration; the gate then shrinks with the alignment (see below).
    double max_correspondence_distance_m = 0.01;
    /// The gate never shrinks below this (metres): several target sample spacings, so that
    /// the whole overlap keeps constraining the pose.
    double min_correspondence_distance_m = 0.005;
    /// After each iteration the gate becomes min(gate, factor × RMS point distance).
    double gate_shrink_factor = 3.0;
    int max_iterations = 30;          ///< Upper bound on linearise-solve-move steps.
    std::size_t sample_count = 3000;  ///< Source points used, spread by voxel sampling.
    RobustKernel robust_kernel = RobustKernel::kTukey;
    /// Kernel width k as a fraction of the current correspondence gate (k follows the gate
    /// as it shrinks, so early iterations far from the optimum keep their correspondences).
    double robust_width_fraction = 1.0;
    /// Stop when a step rotates by less than this (radians) ...
    double rotation_tolerance_rad = 1e-5;
    /// ... and moves the source samples' centroid by less than this (metres).
    double translation_tolerance_m = 1e-6;
    /// Degenerate when the smallest / largest eigenvalue of the scaled 6×6 normal matrix is
    /// below this; the weak directions are then left unchanged by each step.
    double degeneracy_threshold = 1e-3;
    /// Rating: a source sample overlaps the target when its nearest target point lies
    /// within this distance (metres) at the final pose.
    double overlap_distance_m = 0.002;
    /// Below this overlap fraction (of valid source samples) the result is
    /// insufficient_overlap.
    double min_overlap_fraction = 0.05;
    /// Fewer correspondences than this in any iteration: insufficient_overlap.
    std::size_t min_correspondences = 30;
    /// Pairs whose normals (when the source has normals) differ by more are ignored.
    double max_normal_angle_deg = 60.0;
    /// Symmetric polish: after converging with the target's normals, iterate on from there
    /// with the plane of each correspondence given by the mean of both normals (symmetric
    /// point-to-plane, Rusinkiewicz 2019), whose optimum is not biased toward the target's
    /// side. Only when the source has normals; the polished pose is kept only when it
    /// converges within `max_polish_iterations` (else the first result stands).
    bool symmetric_polish = true;
    int max_polish_iterations = 10;     ///< Steps allowed to the symmetric polish.
    bool keep_correspondences = false;  ///< Fill FineRegistrationResult::correspondences.
    /// TBB work unit (samples per chunk). The chunking, not the thread count, fixes the
    /// summation order, so results are identical for any number of threads.
    std::size_t chunk_size = 256;
};

enum class FineRegistrationStatus {
    kConverged,            ///< The last step was below both tolerances.
    kMaxIterations,        ///< Still moving after max_iterations steps (pose is usable).
    kDegenerate,           ///< The constraint slides: see FineRegistrationResult::degeneracy.
    kInsufficientOverlap,  ///< Too few correspondences or too small an overlap.
    kInvalidInput,         ///< Empty, non-finite or inconsistent input; see the message.
};

/// Short English name ("converged", "degenerate", ...), for logs and JSON.
std::string_view to_string(FineRegistrationStatus status);

/// One final correspondence (paper eq. 4 stores these for multi-view registration).
struct FineCorrespondence {
    Eigen::Vector3d source_point_m;  ///< x_i in the source frame (origin included).
    Eigen::Vector3d target_point_m;  ///< y_i in the target frame (origin included).
    Eigen::Vector3f target_normal;   ///< n_i, unit, target frame.
    double residual_m = 0.0;         ///< (T_target_source x_i - y_i)·n_i at the final pose.
    double weight = 1.0;             ///< Robust weight at the final pose, 0..1.
};

/// How well the point-to-plane constraint fixes the six degrees of freedom.
///
/// The 6×6 normal matrix is scaled so that a rotation counts as the displacement it causes
/// at `characteristic_length_m` (RMS distance of the samples from their centroid): the
/// unknowns are (c × L, c̄'), with c̄' the velocity of the centroid, in the target frame.
struct DegeneracyFigure {
    double eigenvalue_ratio = 0.0;  ///< Smallest / largest eigenvalue, 0..1 (1 = isotropic).
    /// Unit eigenvector of the smallest eigenvalue: (rotation axis × L, centroid
    /// translation), target frame. A plane gives a translation in the plane, a cylinder a
    /// combination of rotation about and translation along its axis.
    Eigen::Matrix<double, 6, 1> weakest_direction = Eigen::Matrix<double, 6, 1>::Zero();
    double characteristic_length_m = 0.0;  ///< L above, metres.
};

/// Outcome of a fine registration; every figure is measured at the final pose.
struct FineRegistrationResult {
    FineRegistrationStatus status = FineRegistrationStatus::kInvalidInput;
    std::string message;  ///< What went wrong (empty when converged).
    /// Maps source points into the target frame. The initial guess when the input was
    /// invalid; otherwise the last estimate (also for degenerate and max_iterations).
    Pose T_target_source = Pose::Identity();
    int iterations = 0;  ///< Steps taken (solve + helical move), polish included.
    /// Steps of the symmetric polish (included in `iterations`); 0 when it did not run.
    int polish_iterations = 0;
    bool polished = false;              ///< The symmetric polish converged and gave the final pose.
    std::size_t sample_count = 0;       ///< Valid source samples used.
    std::size_t inlier_count = 0;       ///< Correspondences within the final gate.
    double rms_m = 0.0;                 ///< RMS point-to-plane residual of the inliers.
    double rms_point_distance_m = 0.0;  ///< Paper's ε_pw: RMS point distance, overlapping.
    double overlap_fraction = 0.0;      ///< Samples within overlap_distance_m / samples.
    /// Mean angle between source and target normals of overlapping pairs (degrees);
    /// absent when the source has no normals.
    std::optional<double> normal_deviation_deg;
    DegeneracyFigure degeneracy;
    double time_s = 0.0;                              ///< Wall-clock time of the call, seconds.
    std::vector<FineCorrespondence> correspondences;  ///< Only with keep_correspondences.
};

/// Registers `source` onto `target` starting from `T_target_source_initial`.
///
/// `target` needs normals (unit, target frame); target points with a non-finite position
/// or normal and non-finite source points are ignored. `source` normals are optional and
/// enable the normal-compatibility test and the normal deviation figure. Builds a k-d tree
/// over the target; use the overload below to reuse one. Never throws on bad data.
FineRegistrationResult register_fine(const PointCloud& source, const PointCloud& target,
                                     const Pose& T_target_source_initial,
                                     const FineRegistrationConfig& config);

/// As above with a prebuilt tree over `target.positions` (same order, all finite), so a
/// session can register many scans against one target without rebuilding it.
FineRegistrationResult register_fine(const PointCloud& source, const PointCloud& target,
                                     const KdTree& target_tree, const Pose& T_target_source_initial,
                                     const FineRegistrationConfig& config);

}  // namespace anascan
