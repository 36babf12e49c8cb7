#pragma once
/// \file
/// Time-of-flight depth camera as a scanner: a Z16 camera (e.g. `v4l2:/dev/video2`) plus
/// its pinhole intrinsics → an oriented point cloud in the camera frame (x right, y down,
/// z forward; metres), sensor at the origin, normals toward the sensor.

#include <memory>

#include "anascan/drivers/camera.hpp"
#include "anascan/drivers/scanner.hpp"
#include "anascan/processing/range_grid.hpp"

namespace anascan::drivers {

/// Pinhole intrinsics of the depth image (pixels) and the size of one depth unit.
struct DepthIntrinsics {
    double fx_px = 0.0;
    double fy_px = 0.0;
    double cx_px = 0.0;
    double cy_px = 0.0;
    double depth_unit_m = 0.001;  ///< Metres per Z16 count (1 mm is common).
};

/// Back-projects every non-zero depth pixel: z = d·unit, x = (c − cx)·z/fx,
/// y = (r − cy)·z/fy. Normals from the cross product of the grid neighbours' differences,
/// flipped toward the sensor (the origin). `grid` (optional) receives the pixel → point
/// map. kFormat for a frame that is not Z16, kInvalidArgument for non-positive fx/fy.
Expected<PointCloud> depth_to_point_cloud(const Frame& frame, const DepthIntrinsics& intrinsics,
                                          RangeGrid* grid = nullptr);

/// One depth frame per capture_scan(). Owns the camera. Not thread-safe (see Scanner).
std::unique_ptr<Scanner> make_depth_camera_scanner(std::unique_ptr<Camera> camera,
                                                   const DepthIntrinsics& intrinsics);

}  // namespace anascan::drivers
