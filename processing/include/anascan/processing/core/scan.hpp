#pragma once
/// \file
/// A scan: one capture of one device, with what registration and the session need to know.

#include <chrono>
#include <cstdint>
#include <optional>
#include <string>

#include "anascan/processing/core/point_cloud.hpp"
#include "anascan/processing/core/pose.hpp"

namespace anascan {

/// What kind of device produced a scan; decides noise models and normal orientation.
enum class DeviceKind {
    kUnknown,
    kStructuredLight,  ///< Projector + cameras, sub-millimetre, 0.5-3 m.
    kTimeOfFlight,     ///< Depth camera or terrestrial laser scanner.
    kImported,         ///< Read from a file without device information.
};

/// Metadata of a scan. Frames: the cloud is given in the scan frame; `T_world_scan` places
/// it in the session (world) frame once known.
struct ScanMetadata {
    std::string id;              ///< Unique within a session (file stem for imports).
    std::int64_t sequence = -1;  ///< Order of capture in the session; -1 when unknown.
    std::string device_id;       ///< E.g. "sim:structured-light#0"; empty when unknown.
    DeviceKind device_kind = DeviceKind::kUnknown;
    /// Position of the sensor in the scan frame (metres); orients normals and visibility.
    std::optional<Eigen::Vector3d> sensor_origin_scan_m;
    /// Pose of the scan in the world frame when known (prior or registered).
    std::optional<Pose> T_world_scan;
    std::chrono::system_clock::time_point time{};  ///< Capture time (UTC).
    std::string settings_json;                     ///< Device settings at capture time, JSON text.
};

/// A scan's metadata and points.
struct Scan {
    ScanMetadata meta;
    PointCloud cloud;
};

/// Short name of a device kind ("structured-light", ...), for files and logs.
const char* to_string(DeviceKind kind);

}  // namespace anascan
