#pragma once
// Signed distance to a triangle mesh by angle-weighted pseudo-normals (Bærentzen & Aanæs,
// "Signed distance computation using the angle weighted pseudonormal", IEEE TVCG 2005):
// the sign of (x - q)·n at the closest point q, n the normal of the feature q lies on (the
// triangle's normal inside it, the sum of the two triangles' normals on an edge, the
// angle-weighted sum of the incident triangles' normals at a vertex). Exact on a closed
// manifold mesh. On an open mesh a closest feature on the boundary (an edge of one
// triangle, or a vertex of such an edge) has no inside: it is reported as `boundary`.
// CGAL's AABB tree finds the closest point; only cgal_closest.cpp includes CGAL.
#include <Eigen/Core>
#include <cstddef>
#include <cstdint>
#include <memory>
#include <span>
#include <vector>

namespace anascan::reassembly::detail {

/// The closest point on a set of triangles (CGAL AABB tree behind a plain type).
class ClosestTriangle {
public:
    /// Degenerate (zero-area) triangles are left out.
    ClosestTriangle(std::span<const Eigen::Vector3f> vertices,
                    std::span<const Eigen::Vector3i> triangles);
    ~ClosestTriangle();
    ClosestTriangle(ClosestTriangle&&) noexcept;
    ClosestTriangle& operator=(ClosestTriangle&&) noexcept;
    /// False when there is no triangle; else the closest point and its triangle's index.
    bool closest(const Eigen::Vector3d& x, Eigen::Vector3d& point, std::size_t& triangle) const;

private:
    struct Impl;
    std::unique_ptr<Impl> impl_;
};

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
    ClosestTriangle tree_;
};

}  // namespace anascan::reassembly::detail
