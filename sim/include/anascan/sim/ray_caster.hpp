#pragma once
/// \file
/// Ray casting against a triangle mesh (Embree 3 BVH): the geometry engine of every
/// simulated scanner.

#include <Eigen/Core>
#include <memory>
#include <optional>

#include "anascan/processing/core/expected.hpp"
#include "anascan/processing/core/mesh.hpp"

namespace anascan::sim {

/// Where a ray met the mesh.
struct RayHit {
    double distance_m = 0.0;  ///< Along the (unit) ray direction from its origin.
    int triangle = -1;        ///< Index into the mesh's triangles.
    /// Unit geometric normal of the triangle, from its counter-clockwise winding (outward for
    /// a closed mesh); not flipped toward the ray.
    Eigen::Vector3d normal = Eigen::Vector3d::Zero();
};

/// The point of the mesh nearest to a query point.
struct SurfacePoint {
    double distance_m = 0.0;  ///< From the query point.
    int triangle = -1;        ///< Index into the mesh's triangles.
    Eigen::Vector3d point = Eigen::Vector3d::Zero();
};

/// A ray caster over one mesh, in the mesh's frame (metres). Coordinates are stored as
/// float: keep the mesh within a few kilometres of its origin for sub-micrometre hits.
/// Thread-safe: `cast`, `occluded` and `closest_point` may be called concurrently once created.
class RayCaster {
public:
    /// Builds the BVH. Fails (kEmpty) on a mesh without triangles, (kInvalidArgument) on a
    /// triangle index out of range or a non-finite vertex.
    static Expected<RayCaster> create(const Mesh& mesh);

    RayCaster(RayCaster&&) noexcept;
    RayCaster& operator=(RayCaster&&) noexcept;
    ~RayCaster();

    /// First hit of the ray origin + t * direction with t in [t_min_m, t_max_m];
    /// `direction` must be a unit vector.
    std::optional<RayHit> cast(const Eigen::Vector3d& origin, const Eigen::Vector3d& direction,
                               double t_min_m = 0.0, double t_max_m = INFINITY) const;

    /// True when any triangle lies on the ray for t in [t_min_m, t_max_m] (shadow test).
    bool occluded(const Eigen::Vector3d& origin, const Eigen::Vector3d& direction, double t_min_m,
                  double t_max_m) const;

    /// The nearest point of the mesh within `max_distance_m` of `point` (exact, in double;
    /// Embree's BVH point query), or nothing when no triangle is that close.
    std::optional<SurfacePoint> closest_point(const Eigen::Vector3d& point,
                                              double max_distance_m) const;

    std::size_t triangle_count() const;

private:
    struct Impl;
    explicit RayCaster(std::unique_ptr<Impl> impl);
    std::unique_ptr<Impl> impl_;
};

}  // namespace anascan::sim
