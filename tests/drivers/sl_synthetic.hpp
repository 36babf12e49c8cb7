#pragma once
// A synthetic structured-light rig for tests: a tilted plane about 1 m in front of two
// distortion-free pinhole cameras and a pinhole projector, rendered image by image.

#include <Eigen/Core>
#include <opencv2/core/mat.hpp>
#include <vector>

#include "anascan/drivers/structured_light/gray_code.hpp"
#include "anascan/drivers/structured_light/stereo_calibration.hpp"

namespace anascan::test {

struct SyntheticRig {
    drivers::sl::StereoCalibration calibration;  ///< Two 640x480 cameras, 0.2 m apart.
    drivers::sl::GrayCodeLayout projector{.projector_width_px = 320, .projector_height_px = 200};
    Eigen::Matrix3d projector_K = Eigen::Matrix3d::Identity();
    Pose T_cam1_projector = Pose::Identity();
    Eigen::Vector3d plane_normal = Eigen::Vector3d::UnitZ();  ///< cam1 frame, unit.
    double plane_offset_m = 1.0;                              ///< n . X = offset.
};

SyntheticRig make_rig();

/// The surface point seen by camera `camera` (1 or 2) at pixel position (x, y), cam1 frame.
Eigen::Vector3d surface_point(const SyntheticRig& rig, int camera, double x, double y);

/// Continuous projector coordinates (pixel centres at integers) of camera pixel (x, y).
Eigen::Vector2d projector_coordinates(const SyntheticRig& rig, int camera, double x, double y);

struct RenderOptions {
    int supersample = 1;    ///< s x s samples per camera pixel, averaged.
    bool bilinear = false;  ///< Bilinear projector optics (else nearest projector pixel).
    double black = 20.0;    ///< Grey level of an unlit surface.
    double gain = 200.0;    ///< Grey levels added by a full-white projector pixel.
};

/// The camera's view of each projector image (CV_8UC1, 640x480).
std::vector<cv::Mat> render(const SyntheticRig& rig, int camera,
                            const std::vector<cv::Mat>& patterns, const RenderOptions& options);

}  // namespace anascan::test
