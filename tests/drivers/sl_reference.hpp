#pragma once
// Test/benchmark helpers for structured light: OpenCV's own Gray-code stereo path (the peer)
// and the local-noise figure used to compare clouds.

#include <filesystem>
#include <string>
#include <vector>

#include "anascan/processing/core/point_cloud.hpp"

namespace anascan::test {

/// OpenCV's path as in opencv_contrib's structured_light pointcloud sample, with the
/// rectification stored in the calibration file: rectify (R1/R2/P1/P2; the cam1 images with
/// the file's cam2 maps, as the sample does for this data), GrayCodePattern::decode,
/// reprojectImageTo3D(Q). Points with a disparity, in metres (the file is in mm).
struct OpenCvGrayCodeResult {
    bool ok = false;
    std::string error;
    PointCloud cloud;
    double load_s = 0.0;    ///< Reading + rectifying the images.
    double decode_s = 0.0;  ///< GrayCodePattern::decode.
    double total_s = 0.0;
};

OpenCvGrayCodeResult run_opencv_graycode(const std::filesystem::path& calibration,
                                         const std::vector<std::filesystem::path>& cam1_files,
                                         const std::vector<std::filesystem::path>& cam2_files,
                                         int projector_width_px, int projector_height_px);

/// Median over `samples` points (fixed seed) of the distance from the point to the
/// least-squares plane of its k nearest other points, metres.
double median_local_noise_m(const PointCloud& cloud, int k = 20, std::size_t samples = 20000);

}  // namespace anascan::test
