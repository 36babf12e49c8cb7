#pragma once
// Signed distance to a triangle mesh by angle-weighted pseudo-normals (Bærentzen & Aanæs,
// "Signed distance computation using the angle weighted pseudonormal", IEEE TVCG 2005):
// the sign of (x - q)·n at the closest point q, n the normal of the feature q lies on (the
// triangle's normal inside it, the sum of the two triangles' normals on an edge, the
// angle-weighted sum of the incident triangles' normals at a vertex). Exact on a closed
// manifold mesh. On an open mesh a closest feature on the boundary (an edge of one
// triangle, or a vertex of such an edge) has no inside: it is reported as `boundary`.
// The shared TriangleTree (CGAL's AABB tree) finds the closest point.
#include <Eigen/Core>
#include <cstddef>
#include <cstdint>
#include <memory>
#include <span>
#include <vector>

#include "anascan/processing/spatial/triangle_tree.hpp"

namespace anascan::reassembly::detail {

struct SignedDistance {
    double distance_m = 0.0;  ///< Negative inside.
    bool boundary = false;    ///< The closest feature is on the mesh's boundary.
};

class MeshDistance {
public:
    MeshDistance(std::span<const Eigen::Vector3f> vertices,
                 std::span<const Eigen::Vector3i> triangles);
    /// False for a mesh without triangles.
    bool signed_distance(const Eigen::Vector3d& x, SignedDistance& out) const;

private:
    std::span<const Eigen::Vector3f> vertices_;
    std::span<const Eigen::Vector3i> triangles_;
    std::vector<Eigen::Vector3d> face_normal_, vertex_normal_;
    std::vector<char> vertex_boundary_;
    /// Per triangle t and corner k: the pseudo-normal of the edge from corner k to k + 1,
    /// and whether that edge is on the boundary (one triangle) or non-manifold (three).
    std::vector<Eigen::Vector3d> edge_normal_;
    std::vector<char> edge_boundary_;
    TriangleTree tree_;
};

}  // namespace anascan::reassembly::detail
