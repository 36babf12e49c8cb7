#pragma once
// Moves the surface's vertices onto the measured points' local surface: Poisson's
// isosurface lies on an octree of 2^depth cells, so it rounds arrises by about a cell and
// sits up to half a cell off flat faces; the merged points do not.
#include "anascan/processing/core/mesh.hpp"
#include "anascan/processing/core/point_cloud.hpp"
#include "anascan/processing/spatial/kdtree.hpp"

namespace anascan::surface_detail {

struct PointFitStats {
    std::size_t moved = 0;        ///< Vertices moved onto the points' surface.
    double median_shift_m = 0.0;  ///< Over the moved vertices.
};

/// For each vertex with a merged point within `reach_m`: the merged points within 2 sigma
/// of that nearest point whose normals lie within 30° of its normal (one side of an arris,
/// not both) give a Gaussian-weighted plane (mean position, mean normal), and the vertex is
/// moved along that normal onto it. `mesh` is in `merged`'s frame; vertices without such
/// support (interpolated surface) stay where Poisson put them. `tree` indexes
/// `merged.positions`; `sigma_m` is about the points' spacing.
PointFitStats fit_vertices_to_points(Mesh& mesh, const PointCloud& merged, const KdTree& tree,
                                     double reach_m, double sigma_m);

}  // namespace anascan::surface_detail
