#pragma once
// Midpoint subdivision: every triangle split into four at its edges' midpoints. Closed,
// manifold meshes stay so, and the surface's shape does not change until the new vertices
// are fitted to the points (fit_to_points.hpp).
#include "anascan/processing/core/mesh.hpp"

namespace anascan::surface_detail {

/// The mesh with each triangle split into four; the vertices keep their indices, each edge
/// adds one vertex. Normals, when present, are carried (the mean of the edge's two).
Mesh subdivide_midpoints(const Mesh& mesh);

}  // namespace anascan::surface_detail
