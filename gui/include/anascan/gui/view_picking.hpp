#pragma once
/// \file
/// Picking in the 3D view: the ray through a pixel, a world point's place in the view, and
/// the point a click lands on (the nearest to the eye among those within a few pixels of
/// the ray). Pure maths on the orbit camera's view and perspective; no GL.

#include <Eigen/Geometry>
#include <optional>
#include <span>

#include "anascan/gui/orbit_camera.hpp"

namespace anascan::gui {

/// Normalised device coordinates of the view: x right, y up, both in [-1, 1].
struct ViewRay {
    Eigen::Vector3d origin_m;   ///< The eye, world frame.
    Eigen::Vector3d direction;  ///< Unit, world frame.
};

ViewRay view_ray(const OrbitCamera& camera, double aspect, const Eigen::Vector2d& ndc);

/// Where a world point shows in the view (NDC); nothing when it lies behind the eye.
std::optional<Eigen::Vector2d> project_to_view(const OrbitCamera& camera, double aspect,
                                               const Eigen::Vector3d& point_m);

/// A point hit by a click.
struct PickedPoint {
    std::size_t index = 0;
    double depth_m = 0.0;  ///< Along the ray.
};

/// The point of `points` (placed by T_world_points) nearest the eye among those within
/// `radius_rad` of the ray (seen from the eye); nothing when none is.
std::optional<PickedPoint> pick_point(std::span<const Eigen::Vector3f> points,
                                      const Eigen::Isometry3d& T_world_points, const ViewRay& ray,
                                      double radius_rad);

}  // namespace anascan::gui
