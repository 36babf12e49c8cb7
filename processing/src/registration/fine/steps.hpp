#pragma once
/// \file
/// Private stages of fine registration (fine_registration.cpp reads as these named steps):
/// spread sampling of the source, the parallel correspondence search with accumulation of
/// the 6×6 normal equations of eq. 2, and the (possibly rank-limited) solve.
///
/// Everything here works in the clouds' local float frames: `T_local` maps source-local
/// into target-local coordinates.

#include <Eigen/Core>
#include <cstddef>
#include <cstdint>
#include <limits>
#include <span>
#include <vector>

#include "anascan/processing/core/pose.hpp"
#include "anascan/processing/registration/fine/fine_registration.hpp"
#include "anascan/processing/registration/fine/helical_motion.hpp"
#include "anascan/processing/spatial/kdtree.hpp"

namespace anascan::fine_detail {

using Matrix6d = Eigen::Matrix<double, 6, 6>;
using Vector6d = Eigen::Matrix<double, 6, 1>;

/// The source points the registration uses, in the source local frame.
struct Samples {
    std::vector<Eigen::Vector3f> points;
    std::vector<Eigen::Vector3f> normals;  ///< Empty when the source has none.
    std::vector<std::uint32_t> indices;    ///< Index of each sample in the source cloud.
    Eigen::Vector3d centroid_m = Eigen::Vector3d::Zero();  ///< Source local frame.
    double length_m = 1.0;  ///< RMS distance of the samples from their centroid (> 0).
};

/// Up to `count` finite points spread over the surface: one per occupied voxel (the point
/// nearest the voxel centre), with the voxel size tuned so that about `count` voxels are
/// occupied. Deterministic (depends only on the input order).
Samples sample_spread(const PointCloud& source, std::size_t count);

/// The target as the search sees it.
struct TargetView {
    std::span<const Eigen::Vector3f> points;   ///< Target local frame.
    std::span<const Eigen::Vector3f> normals;  ///< Unit, same length as points.
    const KdTree* tree = nullptr;              ///< Indexes `points`.
};

/// Nearest target point of one sample at the current pose.
struct Match {
    static constexpr std::uint32_t kNone = std::numeric_limits<std::uint32_t>::max();
    std::uint32_t target_index = kNone;  ///< kNone: no usable neighbour.
    float distance_sq_m2 = 0.0f;         ///< Squared point distance to it.
    float residual_m = 0.0f;             ///< (x - y)·n.
    float weight = 0.0f;                 ///< Robust weight; 0 outside the gate.
};

/// What the correspondence pass needs besides the pose.
struct MatchSettings {
    double gate_m = 0.0;  ///< Correspondence gate on the point distance.
    /// Matches farther than this are not searched for (at least the gate, and the
    /// overlap distance the rating counts within).
    double search_bound_m = 0.0;
    RobustKernel kernel = RobustKernel::kTukey;
    double kernel_width_m = 0.0;
    double min_normal_cos = -1.0;  ///< Used only when the samples have normals.
    std::size_t chunk_size = 256;
    /// The plane of a correspondence has the mean of both normals (symmetric
    /// point-to-plane); needs sample normals, else the target normal is used.
    bool symmetric = false;
};

/// The settings of a pass with correspondence gate `gate_m` (metres); `symmetric` selects
/// the symmetric plane (the polish stage).
MatchSettings match_settings(const FineRegistrationConfig& config, double gate_m,
                             bool symmetric = false);

/// Sums of one pass over the inliers: normal equations of eq. 2 in scaled unknowns
/// ξ = (c L, c̄'), c̄' the velocity of the samples' centroid (target local frame).
struct Accumulation {
    Matrix6d H = Matrix6d::Zero();
    Vector6d g = Vector6d::Zero();
    double residual_sq_sum = 0.0;        ///< Σ r² over inliers (unweighted).
    double point_distance_sq_sum = 0.0;  ///< Σ |x - y|² over inliers.
    std::size_t inliers = 0;
    Accumulation& operator+=(const Accumulation& other);
};

/// Finds each sample's nearest target point at `T_local` (stored in `matches`, one per
/// sample) and sums the normal equations over those within the gate. Parallel over fixed
/// chunks of samples; `chunk_sums` is scratch space, summed in chunk order, so the result
/// does not depend on the number of threads.
Accumulation match_and_accumulate(const Samples& samples, const TargetView& target,
                                  const Pose& T_local, const MatchSettings& settings,
                                  std::span<Match> matches, std::vector<Accumulation>& chunk_sums);

/// The scaled normal matrix's conditioning (see DegeneracyFigure).
DegeneracyFigure measure_degeneracy(const Matrix6d& H, double length_m);

/// Solves H ξ = -g for the step (LDLT when well conditioned; otherwise only along the
/// eigen-directions whose eigenvalue reaches threshold × largest) and returns the twist
/// about the target-local origin; `centroid_m` is the samples' centroid (target local).
Twist solve_step(const Accumulation& sums, const DegeneracyFigure& degeneracy,
                 double degeneracy_threshold, double length_m, const Eigen::Vector3d& centroid_m);

/// What the final rating pass needs.
struct RatingInput {
    const Samples& samples;
    const TargetView& target;
    Pose T_local;
    double gate_m = 0.0;  ///< The last correspondence gate.
    Eigen::Vector3d source_origin_m = Eigen::Vector3d::Zero();
    Eigen::Vector3d target_origin_m = Eigen::Vector3d::Zero();
};

/// Rates the pair at the final pose (paper §4.2.2): fills inlier_count, rms_m,
/// rms_point_distance_m, overlap_fraction, normal_deviation_deg, degeneracy and, when the
/// config asks, correspondences. Leaves status, pose and timing alone.
void rate_final_pose(const RatingInput& input, const FineRegistrationConfig& config,
                     FineRegistrationResult& result);

}  // namespace anascan::fine_detail
