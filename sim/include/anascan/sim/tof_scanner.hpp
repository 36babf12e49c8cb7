#pragma once
/// \file
/// Simulated time-of-flight terrestrial laser scanner (like the Riegl LMS-Z420i): a
/// panoramic sweep of azimuth x elevation rays cast into a scene, with Gaussian range
/// noise and mixed pixels at depth edges, delivered as a gridded scan with its true pose.

#include <cstdint>
#include <functional>
#include <string>
#include <vector>

#include "anascan/processing/core/range_grid.hpp"
#include "anascan/processing/core/scan.hpp"
#include "anascan/sim/ray_caster.hpp"

namespace anascan::sim {

struct TofScannerConfig {
    double angular_step_deg = 0.1;       ///< Same step in azimuth and elevation.
    double azimuth_start_deg = 0.0;      ///< First column, counter-clockwise from +x.
    double azimuth_span_deg = 360.0;     ///< The LMS-Z420i sweeps the full circle.
    double elevation_min_deg = -40.0;    ///< Lowest row (80 degrees field of view).
    double elevation_max_deg = 40.0;     ///< Highest row (first grid row).
    double min_range_m = 2.0;            ///< Closer returns are dropped.
    double max_range_m = 800.0;          ///< Farther returns are dropped.
    double range_noise_sigma_m = 0.007;  ///< Gaussian noise along the ray.
    /// Mixed pixels: where the true range breaks by more than this between grid neighbours
    /// (second difference along a row or column), the beam straddles both surfaces...
    double mixed_pixel_jump_m = 0.05;
    /// ...and with this probability returns a range between them (uniform in the gap).
    double mixed_pixel_probability = 0.5;
    std::uint64_t seed = 1;  ///< Same scene, config and seed: identical scan.
    std::string device_id = "sim:tof";
    std::string scan_id = "tof-scan";
};

/// A simulated scan with what only the simulator knows.
struct TofScanResult {
    /// Points in the scanner frame (x: azimuth 0, z: up, origin at the optical centre);
    /// meta.T_world_scan = the true scanner pose, meta.sensor_origin_scan_m = 0, intensity
    /// = albedo x cosine of incidence.
    Scan scan;
    RangeGrid grid;                   ///< rows = elevations (top first), cols = azimuths.
    std::vector<float> true_range_m;  ///< Per point: noise-free range along its ray.
    std::vector<std::uint8_t> mixed;  ///< Per point: 1 for a mixed pixel.
};

/// Progress and abort of a sweep (for the sim:tof device): `keep_going(fraction_done)` is
/// called on the calling thread between blocks of rows; returning false ends the sweep with
/// kCancelled. Empty: the sweep runs to the end.
struct TofSweepControl {
    std::function<bool(double fraction_done)> keep_going;
};

/// Sweeps the scanner at T_world_scanner through the scene of `caster` (world frame).
/// `albedo_of_triangle` gives each triangle's reflectance (empty: 0.5 everywhere).
/// Fails (kInvalidArgument) on a non-positive step, an empty angular window or a grid
/// of more than 10^8 rays.
Expected<TofScanResult> simulate_tof_scan(const RayCaster& caster,
                                          const std::vector<float>& albedo_of_triangle,
                                          const Pose& T_world_scanner,
                                          const TofScannerConfig& config = {},
                                          const TofSweepControl& control = {});

}  // namespace anascan::sim
