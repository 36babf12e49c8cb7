#pragma once
/// \file
/// Down-sampling that does not depend on the frame: points are taken in their order, each
/// unless an already taken point lies closer than the minimum distance (a Poisson-disk
/// sample). Unlike a voxel grid, whose cells are aligned with the frame's axes, a rigidly
/// moved copy of a cloud gives the same points.

#include <cstdint>
#include <vector>

#include "anascan/processing/core/point_cloud.hpp"

namespace anascan {

/// Indices (ascending) of the points kept: every finite point farther than
/// `min_distance_m` from all points kept before it. A non-positive distance keeps every
/// finite point. Deterministic; reentrant.
std::vector<std::uint32_t> min_distance_sample(const PointCloud& cloud, double min_distance_m);

}  // namespace anascan
