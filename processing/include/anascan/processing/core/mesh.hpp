#pragma once
/// \file
/// Triangle meshes (ground-truth scenes, reconstructions, PLY/OBJ/STL exchange).

#include <Eigen/Core>
#include <vector>

#include "anascan/processing/core/point_cloud.hpp"

namespace anascan {

/// Vertices with their attributes and triangles as indices into them.
struct Mesh {
    PointCloud vertices;
    std::vector<Eigen::Vector3i> triangles;  ///< Counter-clockwise seen from outside.
};

}  // namespace anascan
