#pragma once
/// \file
/// Two-ray triangulation of matched cam1/cam2 pixels (midpoint of the shortest segment
/// between the undistorted rays), with the ray gap as the per-point quality.

#include <Eigen/Core>
#include <cstdint>
#include <vector>

#include "anascan/drivers/structured_light/stereo_calibration.hpp"
#include "anascan/drivers/structured_light/stereo_matching.hpp"

namespace anascan::drivers::sl {

struct TriangulationConfig {
    /// Largest distance between the two rays, metres. Approximate calibrations need slack:
    /// the GSoC statue calibration leaves a median gap of ~7 mm at 2.7 m.
    double max_ray_gap_m = 0.03;
    double min_depth_m = 0.05;  ///< Along cam1's optical axis, metres.
    double max_depth_m = 100.0;
};

/// Why a match gave no point.
enum class PointStatus : std::uint8_t { kOk, kRayGap, kDepth, kParallel };

/// One entry per match, in match order.
struct TriangulatedPoints {
    std::vector<Eigen::Vector3f> position_m;  ///< cam1 frame, metres.
    std::vector<float> ray_gap_m;             ///< Shortest distance between the rays, metres.
    std::vector<PointStatus> status;
};

/// Undistorts both pixel sets (cv::undistortPoints, TBB-parallel in blocks) and intersects
/// the rays in cam1's frame. Thread-safe.
TriangulatedPoints triangulate_matches(const StereoMatches& matches,
                                       const StereoCalibration& calibration,
                                       const TriangulationConfig& config);

}  // namespace anascan::drivers::sl
