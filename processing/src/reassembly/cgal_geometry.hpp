#pragma once
// The CGAL parts of block features, behind plain types: Efficient RANSAC plane detection
// (Schnabel et al. 2007) and the minimum-area enclosing rectangle. CGAL is header-heavy:
// only cgal_geometry.cpp includes it.

#include <Eigen/Core>
#include <cstddef>
#include <cstdint>
#include <span>
#include <vector>

namespace anascan::reassembly::detail {

struct RansacParams {
    double epsilon_m = 0.004;
    double cluster_epsilon_m = 0.02;  ///< Inliers farther apart form separate faces.
    double normal_cos = 0.9;
    std::size_t min_points = 100;
    double probability = 0.01;
    std::uint64_t seed = 1;
};

/// A plane n·x = offset_m with the indices (into the input) of its inliers.
struct DetectedPlane {
    Eigen::Vector3d normal;
    double offset_m = 0.0;
    std::vector<std::size_t> indices;
};

/// Planes of the oriented points, largest first; normals point like the inliers' normals.
std::vector<DetectedPlane> detect_planes(std::span<const Eigen::Vector3f> points,
                                         std::span<const Eigen::Vector3f> normals,
                                         const RansacParams& params);

/// A rectangle in the plane: centre, unit direction of its longer side, side lengths.
struct Rectangle2 {
    Eigen::Vector2d centre = Eigen::Vector2d::Zero();
    Eigen::Vector2d long_axis = Eigen::Vector2d::UnitX();
    double long_m = 0.0, short_m = 0.0;
};

/// The minimum-area rectangle enclosing the points (zero for fewer than three).
Rectangle2 min_area_rectangle(std::span<const Eigen::Vector2d> points);

}  // namespace anascan::reassembly::detail
