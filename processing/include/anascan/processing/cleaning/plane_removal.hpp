#pragma once
/// \file
/// The dominant plane of a cloud (the ground under a stone) by RANSAC with a least-squares
/// refit, and its removal. Paper §4.1 removes background points; registration may still
/// use them (they stabilise it), so finding and removing are separate calls.

#include <Eigen/Core>
#include <cstddef>
#include <cstdint>
#include <vector>

#include "anascan/processing/core/point_cloud.hpp"

namespace anascan {

struct PlaneFitConfig {
    double distance_threshold_m = 0.002;  ///< Inlier band half-width, metres.
    int max_iterations = 1000;            ///< RANSAC hypotheses at most (adaptive below).
    double confidence = 0.999;            ///< Stop once a better plane is this unlikely.
    double min_inlier_fraction = 0.2;     ///< Of the finite points, for kOk.
    std::uint64_t seed = 1;               ///< Random sampling seed: fixed, reproducible.
};

/// Plane n · x + offset_m = 0 in the cloud's local frame; n is a unit vector.
struct Plane {
    Eigen::Vector3d normal = Eigen::Vector3d::UnitZ();
    double offset_m = 0.0;
    /// Signed distance of a local position, metres (positive on the normal's side).
    double signed_distance_m(const Eigen::Vector3f& p) const {
        return normal.dot(p.cast<double>()) + offset_m;
    }
};

enum class PlaneFitStatus {
    kOk,
    kTooFewPoints,     ///< Fewer than 3 finite points.
    kNoDominantPlane,  ///< The best plane holds at most min_inlier_fraction; plane is that.
};

struct PlaneFitResult {
    PlaneFitStatus status = PlaneFitStatus::kTooFewPoints;
    /// The normal points to the side holding more of the other points (the stone on the
    /// ground), +z of the local frame when there are none.
    Plane plane;
    std::vector<std::size_t> inlier_indices;  ///< Increasing.
    double inlier_fraction = 0.0;             ///< Inliers / finite points.
    double rms_m = 0.0;                       ///< RMS distance of the inliers to the plane.
    int iterations = 0;                       ///< RANSAC hypotheses evaluated.
};

/// RANSAC over random point triples (fixed seed), then a least-squares (PCA) refit on the
/// inliers, repeated once with the refitted plane's inliers.
PlaneFitResult find_dominant_plane(const PointCloud& cloud, const PlaneFitConfig& config);

struct PlaneRemovalResult {
    PlaneFitResult fit;
    std::vector<std::size_t> kept_indices;  ///< Finite non-inliers; all finite when not kOk.
};

/// Finds the dominant plane and returns the indices of the points off it; when no plane
/// is dominant nothing but non-finite points is removed.
PlaneRemovalResult remove_dominant_plane(const PointCloud& cloud, const PlaneFitConfig& config);

}  // namespace anascan
