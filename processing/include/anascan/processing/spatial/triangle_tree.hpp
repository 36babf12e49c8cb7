#pragma once
/// \file
/// Closest points on, and segment hits with, a set of triangles: CGAL's AABB tree behind a
/// plain type (only spatial/triangle_tree.cpp includes CGAL). The one exact point-to-mesh
/// query of processing: the surface evaluation, the reassembly's signed distance and the
/// visibility of a true surface all use it.

#include <Eigen/Core>
#include <cstddef>
#include <memory>
#include <span>

namespace anascan {

/// Immutable after construction; thread-safe for concurrent queries.
class TriangleTree {
public:
    /// Vertices in any frame (queries use the same); degenerate (zero-area) triangles are
    /// left out. The spans are copied: they need not outlive the tree.
    TriangleTree(std::span<const Eigen::Vector3f> vertices,
                 std::span<const Eigen::Vector3i> triangles);
    ~TriangleTree();
    TriangleTree(TriangleTree&&) noexcept;
    TriangleTree& operator=(TriangleTree&&) noexcept;

    /// False when there is no triangle; else the closest point and its triangle's index.
    bool closest(const Eigen::Vector3d& x, Eigen::Vector3d& point, std::size_t& triangle) const;
    /// Whether the segment from `a` to `b` meets any triangle.
    bool segment_hits(const Eigen::Vector3d& a, const Eigen::Vector3d& b) const;
    /// Triangles kept (non-degenerate).
    std::size_t size() const;

private:
    struct Impl;
    std::unique_ptr<Impl> impl_;
};

}  // namespace anascan
