#pragma once
/// \file
/// Rigid poses. Named by frames: `T_to_from` maps a point in frame `from` into frame `to`
/// (`p_world = T_world_scan * p_scan`).

#include <Eigen/Geometry>

#include "anascan/processing/core/point_cloud.hpp"

namespace anascan {

/// A rigid transform (rotation + translation, metres).
using Pose = Eigen::Isometry3d;

/// Rotation angle of `T_a_b` in degrees, in [0, 180].
double rotation_angle_deg(const Pose& T_a_b);

/// Rotation angle (degrees) and translation distance (metres) between two estimates of the
/// same pose: the angle and translation of `a.inverse() * b`.
struct PoseDifference {
    double rotation_deg = 0.0;
    double translation_m = 0.0;
};
PoseDifference pose_difference(const Pose& a, const Pose& b);

/// Builds a pose from a unit quaternion (w, x, y, z) and a translation (metres).
Pose make_pose(const Eigen::Quaterniond& q, const Eigen::Vector3d& t_m);

/// Re-expresses a cloud in another frame: world positions become `T_to_from * p`. The
/// origin moves with the transform and local offsets are only rotated, so no precision is
/// lost for large site coordinates. Normals are rotated.
PointCloud transformed(const PointCloud& cloud_from, const Pose& T_to_from);

/// Re-orthonormalises the rotation part (after accumulated products or parsing 4x4 text).
Pose orthonormalized(const Pose& T);

/// A sensor pose at `eye` looking at `target` along its +z, with +y (image down) toward -up
/// (the OpenCV camera frame).
Pose look_at(const Eigen::Vector3d& eye, const Eigen::Vector3d& target,
             const Eigen::Vector3d& up = Eigen::Vector3d::UnitZ());

}  // namespace anascan
