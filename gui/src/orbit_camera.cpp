#include "anascan/gui/orbit_camera.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>

namespace anascan::gui {
namespace {

constexpr double kOrbitRadPerPx = 0.008;
constexpr double kZoomPerStep = 0.85;
constexpr double kMaxPitchRad = 0.49 * std::numbers::pi;

/// Unit vector from the target toward the eye.
Eigen::Vector3d eye_direction(double yaw_rad, double pitch_rad) {
    return {std::cos(pitch_rad) * std::cos(yaw_rad), std::cos(pitch_rad) * std::sin(yaw_rad),
            std::sin(pitch_rad)};
}

}  // namespace

void OrbitCamera::orbit(double dx_px, double dy_px) {
    yaw_rad_ -= dx_px * kOrbitRadPerPx;
    pitch_rad_ = std::clamp(pitch_rad_ + dy_px * kOrbitRadPerPx, -kMaxPitchRad, kMaxPitchRad);
}

void OrbitCamera::pan(double dx_px, double dy_px, double viewport_height_px) {
    if (viewport_height_px <= 0.0) return;
    // Metres per pixel at the target's depth.
    const double m_per_px = 2.0 * distance_m_ * std::tan(0.5 * fov_y_rad_) / viewport_height_px;
    const Eigen::Matrix3d R_world_camera = view().rotation().transpose();
    target_m_ += R_world_camera * Eigen::Vector3d(-dx_px * m_per_px, dy_px * m_per_px, 0.0);
}

void OrbitCamera::zoom(double wheel_steps) {
    distance_m_ = std::max(min_distance_m_, distance_m_ * std::pow(kZoomPerStep, wheel_steps));
}

void OrbitCamera::fit(const BoundingSphere& sphere, double aspect) {
    target_m_ = sphere.centre_m;
    const double radius_m = std::max(sphere.radius_m, 1e-3);
    // The sphere touches the narrower field of view, with a 10 % margin.
    const double half_fov_x_rad = std::atan(std::tan(0.5 * fov_y_rad_) * std::max(aspect, 1e-3));
    const double half_fov_rad = std::min(0.5 * fov_y_rad_, half_fov_x_rad);
    distance_m_ = 1.1 * radius_m / std::sin(half_fov_rad);
    min_distance_m_ = 1e-3 * radius_m;
}

Eigen::Vector3d OrbitCamera::eye_m() const {
    return target_m_ + distance_m_ * eye_direction(yaw_rad_, pitch_rad_);
}

Eigen::Isometry3d OrbitCamera::view() const {
    const Eigen::Vector3d back = eye_direction(yaw_rad_, pitch_rad_);  // camera +z
    const Eigen::Vector3d right = Eigen::Vector3d::UnitZ().cross(back).normalized();
    const Eigen::Vector3d up = back.cross(right);
    Eigen::Matrix3d R_world_camera;
    R_world_camera << right, up, back;
    Eigen::Isometry3d T_camera_world = Eigen::Isometry3d::Identity();
    T_camera_world.linear() = R_world_camera.transpose();
    T_camera_world.translation() = -(R_world_camera.transpose() * eye_m());
    return T_camera_world;
}

Eigen::Matrix4d OrbitCamera::projection(double aspect) const {
    const double near_m = std::max(1e-4, 0.01 * distance_m_);
    const double far_m = 100.0 * distance_m_;
    const double f = 1.0 / std::tan(0.5 * fov_y_rad_);
    Eigen::Matrix4d P = Eigen::Matrix4d::Zero();
    P(0, 0) = f / std::max(aspect, 1e-6);
    P(1, 1) = f;
    P(2, 2) = (far_m + near_m) / (near_m - far_m);
    P(2, 3) = 2.0 * far_m * near_m / (near_m - far_m);
    P(3, 2) = -1.0;
    return P;
}

}  // namespace anascan::gui
