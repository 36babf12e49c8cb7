#include "anascan/gui/view_picking.hpp"

#include <cmath>

namespace anascan::gui {

ViewRay view_ray(const OrbitCamera& camera, double aspect, const Eigen::Vector2d& ndc) {
    const double t = std::tan(0.5 * camera.fov_y_rad());
    const Eigen::Vector3d in_camera(ndc.x() * t * aspect, ndc.y() * t, -1.0);
    const Eigen::Isometry3d T_world_camera = camera.view().inverse();
    return {.origin_m = camera.eye_m(),
            .direction = (T_world_camera.linear() * in_camera).normalized()};
}

std::optional<Eigen::Vector2d> project_to_view(const OrbitCamera& camera, double aspect,
                                               const Eigen::Vector3d& point_m) {
    const Eigen::Vector3d c = camera.view() * point_m;
    if (c.z() >= 0.0) return std::nullopt;
    const double t = std::tan(0.5 * camera.fov_y_rad());
    return Eigen::Vector2d(c.x() / (-c.z() * t * aspect), c.y() / (-c.z() * t));
}

std::optional<PickedPoint> pick_point(std::span<const Eigen::Vector3f> points,
                                      const Eigen::Isometry3d& T_world_points, const ViewRay& ray,
                                      double radius_rad) {
    // In the points' frame: one transform of the ray instead of one per point.
    const Eigen::Isometry3d T_points_world = T_world_points.inverse();
    const Eigen::Vector3d o = T_points_world * ray.origin_m;
    const Eigen::Vector3d d = T_points_world.linear() * ray.direction;
    const double tan_radius = std::tan(radius_rad);
    std::optional<PickedPoint> best;
    for (std::size_t i = 0; i < points.size(); ++i) {
        const Eigen::Vector3d v = points[i].cast<double>() - o;
        const double depth = v.dot(d);
        if (depth <= 0.0 || (best && depth >= best->depth_m)) continue;
        if ((v - depth * d).norm() <= depth * tan_radius) best = PickedPoint{i, depth};
    }
    return best;
}

}  // namespace anascan::gui
