#pragma once
/// \file
/// The simulated time-of-flight terrestrial scanner as a device (`sim:tof[/SCENE]`): a
/// drivers::Scanner whose capture_scan sweeps the simulated scanner (tof_scanner.hpp)
/// through a scene from a tripod station, returning the scan with its true pose.

#include <memory>
#include <string>

#include "anascan/sim/sim_scanner.hpp"
#include "anascan/sim/tof_scanner.hpp"

namespace anascan::sim {

/// Where the tripod stands, around the block's centre (see tripod_pose()).
struct SimStation {
    double azimuth_deg = 0.0;  ///< Counter-clockwise from world +x.
    double distance_m = 3.5;   ///< Horizontal distance to the block's centre.
    double height_m = 1.5;     ///< Optical centre above the ground.
};

struct SimTofScannerConfig {
    std::string uri = "sim:tof";  ///< Names the device in info() and in every error.
    SceneConfig scene;            ///< What it looks at (e.g. named_scene("octagon-block")).
    TofScannerConfig scanner;     ///< Sweep, noise; angular step and range are settings.
    SimStation station;           ///< Station of the first capture.
    /// After each capture the tripod moves this far around the block, so that a capture
    /// session records several stations without a sim-only call; 0 keeps it in place.
    double advance_deg = 90.0;
    std::shared_ptr<SimWorldCache> worlds;    ///< Shared scenes; empty: a private cache.
    std::shared_ptr<SimDeviceFaults> faults;  ///< Injected unplug/stall; may be empty.
};

/// The device. Settings: angular_step_deg [0.02, 5], min/max_range_m within [2, 800].
/// Not thread-safe (see drivers::Scanner); the scene is shared read-only.
class SimTofScanner final : public SimScanner {
public:
    /// Opens at once; the scene is built (or taken from the cache) at the first capture:
    /// about a second for octagon-block.
    static std::unique_ptr<SimTofScanner> open(SimTofScannerConfig config);

    std::string calibration_json() const override;
    /// A full sweep, in 20 blocks of rows: a stop or the timeout ends it within one.
    Expected<Scan> capture_scan(const drivers::CaptureControl& control) override;

    /// Sim-only: the station of the next capture.
    void move_to(const SimStation& station) { station_ = station; }
    const SimStation& station() const { return station_; }
    /// True pose of the next capture (world frame).
    Pose station_pose() const;

private:
    explicit SimTofScanner(SimTofScannerConfig config);

    SimTofScannerConfig config_;
    SimStation station_;
};

}  // namespace anascan::sim
