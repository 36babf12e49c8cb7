#pragma once
/// \file
/// Video4Linux2 cameras (`v4l2:/dev/videoN`): query capabilities, enumerate and set the
/// format, stream with read() or user-pointer buffers, dequeue with a timeout, and end
/// cleanly with kDisconnected when the camera is unplugged (ENODEV). Grey, YUYV, MJPEG and
/// 16-bit Z16 depth frames.

#include <filesystem>
#include <memory>
#include <string>
#include <vector>

#include "anascan/drivers/camera.hpp"
#include "anascan/drivers/device_registry.hpp"

namespace anascan::drivers {

/// How frames travel from the driver. read() copies once and works under umockdev;
/// user pointers are what UVC webcams offer (they have no read()).
enum class V4l2IoMethod { kAuto, kRead, kUserPointer };

struct V4l2CameraConfig {
    std::string device_path = "/dev/video0";
    V4l2IoMethod io = V4l2IoMethod::kAuto;  ///< kAuto: read() when offered, else user pointers.
    int buffer_count = 4;                   ///< User-pointer buffers queued at once.
};

/// Opens and queries the device (kDisconnected when the node is missing, kBusy when
/// another program holds it, kUnsupported when it is not a capture device).
Expected<std::unique_ptr<Camera>> open_v4l2_camera(const V4l2CameraConfig& config);

/// Capture nodes listed in `sysfs_dir` (each entry's `name` is the model).
std::vector<DeviceInfo> enumerate_v4l2_cameras(
    const std::filesystem::path& sysfs_dir = "/sys/class/video4linux");

/// The `v4l2:` backend for the registry.
Backend make_v4l2_backend();

}  // namespace anascan::drivers
