#pragma once
/// \file
/// Where simulated scanners stand: viewpoints around a target, as true sensor poses.

#include <Eigen/Core>

#include "anascan/processing/core/pose.hpp"

namespace anascan::sim {

/// A position on a sphere around a target: azimuth counter-clockwise from world +x,
/// elevation above the horizontal.
struct Viewpoint {
    double azimuth_deg = 0.0;
    double elevation_deg = 30.0;
    double distance_m = 1.0;
};

/// A camera-like sensor (OpenCV frame: +z toward the target, +y image down) at the
/// viewpoint around `target_world`.
Pose sensor_looking_at(const Eigen::Vector3d& target_world, const Viewpoint& view);

/// A terrestrial scanner on a tripod: z up, x (azimuth 0) pointing horizontally at the
/// target, its optical centre `height_m` above the ground and `distance_m` from the target
/// horizontally, at `azimuth_deg` around it.
Pose tripod_pose(const Eigen::Vector3d& target_world, double azimuth_deg, double distance_m,
                 double height_m);

}  // namespace anascan::sim
