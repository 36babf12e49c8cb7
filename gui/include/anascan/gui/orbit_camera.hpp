#pragma once
/// \file
/// An orbit camera around a target point: orbit (yaw/pitch), pan (moves the target in the
/// view plane), zoom (distance), and "fit to stone" from a bounding sphere. Pure maths in
/// double: the view matrix is exact for site coordinates far from the origin.

#include <Eigen/Geometry>

namespace anascan::gui {

/// A bounding sphere in world coordinates (metres).
struct BoundingSphere {
    Eigen::Vector3d centre_m = Eigen::Vector3d::Zero();
    double radius_m = 0.0;
};

/// Camera state; the world's +z is up. Not thread-safe.
class OrbitCamera {
public:
    /// Rotates around the target: dx, dy in pixels of mouse motion.
    void orbit(double dx_px, double dy_px);
    /// Moves the target in the view plane so that the point under the cursor follows it.
    void pan(double dx_px, double dy_px, double viewport_height_px);
    /// Zooms by mouse wheel steps (positive = closer), never through the target.
    void zoom(double wheel_steps);
    /// Looks at the whole sphere from the current direction, filling the narrower side of
    /// a view of that aspect (width / height).
    void fit(const BoundingSphere& sphere, double aspect = 1.0);

    /// T_camera_world: world → camera (OpenGL convention: looking down -z, y up).
    Eigen::Isometry3d view() const;
    /// Perspective projection for the aspect width/height; near/far follow the distance.
    Eigen::Matrix4d projection(double aspect) const;
    /// Camera position in world coordinates, metres.
    Eigen::Vector3d eye_m() const;

    const Eigen::Vector3d& target_m() const { return target_m_; }
    double distance_m() const { return distance_m_; }
    double fov_y_rad() const { return fov_y_rad_; }

private:
    Eigen::Vector3d target_m_ = Eigen::Vector3d::Zero();
    double distance_m_ = 3.0;
    double yaw_rad_ = 0.6;     ///< Around world z.
    double pitch_rad_ = 0.45;  ///< Elevation above the horizontal plane.
    double fov_y_rad_ = 0.8;
    double min_distance_m_ = 0.01;
};

}  // namespace anascan::gui
