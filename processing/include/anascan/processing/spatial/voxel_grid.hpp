#pragma once
/// \file
/// Voxel down-sampling: one point per occupied voxel, the mean of the points inside it.

#include "anascan/processing/core/point_cloud.hpp"

namespace anascan {

struct VoxelDownsampleConfig {
    double voxel_size_m = 0.002;  ///< Edge length of a cubic voxel, metres (> 0).
};

/// Replaces the points of each occupied voxel by their mean position; normals are averaged
/// and renormalised, colours, intensity and confidence averaged. Voxels are aligned with
/// the local frame's origin. Output order is by voxel key, so the result does not depend on
/// input order or thread count. Non-finite points are dropped. A non-positive voxel size
/// returns a copy of the input.
PointCloud voxel_downsample(const PointCloud& cloud, const VoxelDownsampleConfig& config);

}  // namespace anascan
