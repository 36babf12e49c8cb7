#pragma once
// Shared by `register` and `align`: the sensor options and loading a scan from a PLY.
#include <CLI/CLI.hpp>
#include <Eigen/Core>
#include <optional>
#include <string>
#include <vector>

#include "anascan/processing/core/expected.hpp"
#include "anascan/processing/core/point_cloud.hpp"

namespace anascan::cli {

/// Where estimated normals point: toward a sensor position in each scan's own frame, or,
/// by default, toward the side each scan was seen from (orient_as_range_scan).
struct SensorOptions {
    std::vector<double> origin_m{0.0, 0.0, 0.0};
    bool no_sensor = false;  ///< Explicitly the default: the seen side.
    bool sensor_z = false;   ///< (0,0,1) m, for orienting normals only.
    /// --sensor-origin was given: the position is where the scans were taken from (enables
    /// the free-space check of `register`).
    bool origin_given = false;
};

/// Adds --sensor-origin X Y Z, --sensor-z and --no-sensor to `cmd`.
void add_sensor_options(CLI::App* cmd, SensorOptions& options);

/// The sensor position (metres, scan frame), or nullopt for the seen side.
std::optional<Eigen::Vector3d> sensor_origin(const SensorOptions& options);

/// Reads a PLY's vertices (with its normals when it has them).
Expected<PointCloud> load_ply_cloud(const std::string& path);

}  // namespace anascan::cli
