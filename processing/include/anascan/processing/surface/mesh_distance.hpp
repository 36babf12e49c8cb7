#pragma once
/// \file
/// Distances from points to a triangle mesh and uniform samples of a mesh's surface, for
/// evaluating reconstructions against a reference (accuracy and completeness).

#include <Eigen/Core>
#include <cstddef>
#include <cstdint>
#include <vector>

#include "anascan/processing/core/mesh.hpp"
#include "anascan/processing/spatial/triangle_tree.hpp"

namespace anascan {

/// Exact unsigned distance from world-frame points to a mesh's surface (the shared
/// TriangleTree). Copies what it needs: the mesh need not outlive it. Thread-safe for
/// concurrent queries after construction.
class MeshDistance {
public:
    explicit MeshDistance(const Mesh& mesh);

    /// Distance (metres) from a world-frame point to the surface; +inf for a mesh without
    /// triangles.
    double distance_m(const Eigen::Vector3d& point_world_m) const;
    /// The distance and the closest triangle's index; false for a mesh without triangles.
    bool closest(const Eigen::Vector3d& point_world_m, double& distance_m,
                 std::size_t& triangle) const;

private:
    Eigen::Vector3d origin_m_;
    TriangleTree tree_;
};

/// A point on a triangle and which triangle it lies on.
struct SurfaceSample {
    Eigen::Vector3d position_m;  ///< World frame.
    std::uint32_t triangle = 0;
};

/// About one sample per `spacing_m`^2 of area, uniformly distributed (seeded, so the same
/// mesh gives the same samples).
std::vector<SurfaceSample> sample_surface(const Mesh& mesh, double spacing_m,
                                          std::uint32_t seed = 1);

}  // namespace anascan
