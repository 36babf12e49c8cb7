#pragma once
/// \file
/// Accuracy of a simulated scan: the distance of every point to the ground-truth mesh.

#include <cstddef>
#include <vector>

#include "anascan/processing/core/point_cloud.hpp"
#include "anascan/processing/core/pose.hpp"
#include "anascan/sim/ray_caster.hpp"

namespace anascan::sim {

/// Distance of each point (T_mesh_cloud * point) to the nearest triangle, metres; points
/// farther than max_distance_m get max_distance_m. Parallel, deterministic.
std::vector<double> surface_distances(const PointCloud& cloud, const Pose& T_mesh_cloud,
                                      const RayCaster& mesh, double max_distance_m);

struct SurfaceDistanceSummary {
    std::size_t points = 0;
    std::size_t beyond_max = 0;    ///< Points at max_distance_m or farther.
    double within_fraction = 0.0;  ///< Share of points within the tolerance.
    double median_m = 0.0;
    double rms_m = 0.0;         ///< Over every point (capped at max_distance_m).
    double rms_best95_m = 0.0;  ///< Over the 95 % closest points.
};

SurfaceDistanceSummary summarize_distances(std::vector<double> distances_m, double tolerance_m,
                                           double max_distance_m);

}  // namespace anascan::sim
