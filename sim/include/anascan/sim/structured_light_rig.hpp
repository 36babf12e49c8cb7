#pragma once
/// \file
/// Geometry of a simulated structured-light head (PT-M 1024-like): a projector between two
/// verging cameras, pinhole models without distortion, and its stereo calibration written
/// as OpenCV FileStorage YAML with the keys of the GSoC 2015 statue dataset.

#include <Eigen/Core>
#include <filesystem>

#include "anascan/drivers/structured_light/stereo_calibration.hpp"
#include "anascan/processing/core/expected.hpp"
#include "anascan/processing/core/pose.hpp"

namespace anascan::sim {

/// A pinhole camera or projector (OpenCV frame: x right, y down, z forward; pixel (i, j)
/// centred at continuous coordinates (i, j)).
struct PinholeModel {
    int width_px = 0, height_px = 0;
    double fx_px = 0.0, fy_px = 0.0, cx_px = 0.0, cy_px = 0.0;
    Pose T_world_device = Pose::Identity();

    /// Unit ray through continuous pixel (x, y), world frame.
    Eigen::Vector3d ray_world(double x_px, double y_px) const;
    /// Pixel of a world point and its depth (z in the device frame, metres).
    Eigen::Vector3d project(const Eigen::Vector3d& p_world) const;
};

struct StructuredLightRig {
    PinholeModel projector;
    PinholeModel cam1;  ///< Left camera (negative rig x).
    PinholeModel cam2;  ///< Right camera.
};

/// Defaults: two 1600x1200 cameras (f = 2700 px, 33 x 25 degrees, 0.37 mm per pixel at
/// 1 m) 0.4 m apart, a 1280x800 projector (f = 1700 px) in the middle, all converging on
/// the projector axis at 1 m.
struct StructuredLightRigConfig {
    int camera_width_px = 1600, camera_height_px = 1200;
    double camera_focal_px = 2700.0;
    int projector_width_px = 1280, projector_height_px = 800;
    double projector_focal_px = 1700.0;
    double baseline_m = 0.4;          ///< Between the camera centres.
    double working_distance_m = 1.0;  ///< Where the optical axes meet.
};

/// The rig with its projector frame at T_world_rig.
StructuredLightRig make_structured_light_rig(const StructuredLightRigConfig& config,
                                             const Pose& T_world_rig);

/// The rig's exact stereo calibration as the decoder takes it (metres, cam1 = rig.cam1).
drivers::sl::StereoCalibration stereo_calibration(const StructuredLightRig& rig);

/// Writes the stereo calibration as OpenCV FileStorage YAML: cam1_intrinsics,
/// cam1_distorsion (zeros), cam1_size, cam2_*, R, T (millimetres) with
/// X_cam2 = R X_cam1 + T (OpenCV stereoCalibrate convention; NOT swapped like the statue
/// data), RT_cam1_2_cam2, stereo_error, rectification R1 R2 P1 P2 Q (cv::stereoRectify),
/// plus the simulation's truth: proj_intrinsics, proj_size, T_world_cam1_m, T_world_proj_m,
/// and, when given, the pattern layout (pattern_phase_steps, pattern_phase_period_px: see
/// drivers::sl::load_pattern_layout).
Expected<void> write_stereo_calibration(
    const std::filesystem::path& path, const StructuredLightRig& rig,
    const std::optional<drivers::sl::RecordedPatternLayout>& layout = std::nullopt);

}  // namespace anascan::sim
