#pragma once
/// \file
/// Distances from points to a triangle mesh and uniform samples of a mesh's surface, for
/// evaluating reconstructions against a reference (accuracy and completeness).

#include <Eigen/Core>
#include <cstdint>
#include <memory>
#include <vector>

#include "anascan/processing/core/mesh.hpp"

namespace anascan {

/// Unsigned distance from points to a mesh's surface: the closest point over the triangles
/// around the `k` vertices nearest to the query. Exact when the closest triangle has one of
/// those vertices, which holds when triangles are small against the query's distance or
/// the mesh is evenly sampled. Keeps a reference: the mesh must outlive it. Thread-safe for
/// concurrent queries after construction.
class MeshDistance {
public:
    explicit MeshDistance(const Mesh& mesh, int k_vertices = 8);
    ~MeshDistance();
    MeshDistance(MeshDistance&&) noexcept;
    MeshDistance& operator=(MeshDistance&&) noexcept;

    /// Distance (metres) from a world-frame point to the surface; +inf for an empty mesh.
    double distance_m(const Eigen::Vector3d& point_world_m) const;

private:
    struct Impl;
    std::unique_ptr<Impl> impl_;
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

/// Distance from p to triangle (a, b, c) (closest point by Voronoi regions, Ericson 2005 §5.1.5).
double point_triangle_distance(const Eigen::Vector3d& p, const Eigen::Vector3d& a,
                               const Eigen::Vector3d& b, const Eigen::Vector3d& c);

}  // namespace anascan
