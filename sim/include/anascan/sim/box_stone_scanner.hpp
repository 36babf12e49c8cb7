#pragma once
/// \file
/// A small analytic stand-in for a scanned stone: a rectangular block scanned from
/// viewpoints around it by ray casting, with the true pose of every scan. Used by the
/// synthetic example when no real data is at hand and by tests that need known poses.
/// (The full procedural Octagon-like stones and simulated devices come with the drivers
/// issue.)

#include <cstdint>
#include <vector>

#include "anascan/processing/core/scan.hpp"

namespace anascan::sim {

struct BoxStoneScanConfig {
    Eigen::Vector3d size_m{0.8, 0.5, 0.4};  ///< Block edge lengths, metres, centred at 0.
    int view_count = 6;                     ///< Viewpoints evenly spaced around the block.
    double distance_m = 1.2;                ///< Sensor distance from the block centre.
    double elevation_deg = 30.0;            ///< Sensor height above the block's mid-plane.
    double angular_step_deg = 0.15;         ///< Ray spacing of the simulated sensor.
    double noise_sigma_m = 0.0001;          ///< Gaussian range noise, metres.
    std::uint32_t seed = 1;                 ///< Fixed seed: same config, same scans.
};

/// Scans of the block, each in its own sensor frame (sensor at the origin looking along
/// +z), with `meta.T_world_scan` set to the true pose, `meta.sensor_origin_scan_m` to zero
/// and normals pointing toward the sensor.
std::vector<Scan> scan_box_stone(const BoxStoneScanConfig& config);

}  // namespace anascan::sim
