#pragma once
/// \file
/// Time-of-flight depth camera as a scanner: a Z16 camera (e.g. `v4l2:/dev/video2`) plus
/// its pinhole intrinsics → an oriented point cloud in the camera frame (x right, y down,
/// z forward; metres), sensor at the origin, normals toward the sensor.

#include <memory>

#include "anascan/drivers/camera.hpp"
#include "anascan/drivers/device_registry.hpp"
#include "anascan/drivers/scanner.hpp"
#include "anascan/processing/core/range_grid.hpp"

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

/// The `depth:` backend: `depth:CAMERA_URI?fx_px=F&fy_px=F&cx_px=C&cy_px=C[&depth_unit_m=U]`
/// (e.g. `depth:v4l2:/dev/video2?fx_px=580&fy_px=580&cx_px=320&cy_px=240`): the Z16 camera
/// opened by `cameras`, as a scanner with those intrinsics (pixels; unit default 0.001 m).
/// Not enumerable. kInvalidArgument naming the key for missing or bad intrinsics.
Backend make_depth_scanner_backend(std::shared_ptr<const DeviceRegistry> cameras);

}  // namespace anascan::drivers
