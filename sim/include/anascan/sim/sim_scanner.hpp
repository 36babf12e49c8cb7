#pragma once
/// \file
/// What the simulated scanners share as devices: info, capabilities, validated settings,
/// the scene they look at (built at the first capture, shared through a SimWorldCache),
/// the sim-only placement of the block, injected faults and the metadata of each scan.

#include <memory>
#include <optional>

#include "anascan/drivers/scanner.hpp"
#include "anascan/sim/scene.hpp"
#include "anascan/sim/sim_device_faults.hpp"
#include "anascan/sim/sim_world.hpp"

namespace anascan::sim {

/// What a simulated scanner is made of (see SimScanner).
struct SimScannerParts {
    drivers::DeviceInfo info;
    drivers::Capabilities caps;
    drivers::DeviceSettings settings;  ///< Every setting the device has.
    SceneConfig scene;
    std::shared_ptr<SimWorldCache> worlds;  ///< Empty: a private cache.
    std::shared_ptr<SimDeviceFaults> faults;
};

/// Base of sim:tof and sim:structured-light. Not thread-safe (see drivers::Scanner).
class SimScanner : public drivers::Scanner {
public:
    const drivers::DeviceInfo& info() const override { return info_; }
    const drivers::Capabilities& capabilities() const override { return caps_; }
    drivers::DeviceSettings settings() const override { return settings_; }
    Expected<void> configure(const drivers::DeviceSettings& requested) override;
    void close() override { closed_ = true; }

    /// Sim-only: lays the block differently (e.g. resting_face kPosZ = turned over); the
    /// scene is rebuilt at the next capture.
    void place_block(const BlockPlacement& placement);
    /// Sim-only: faults to inject from now on (unplug, stall); shared with the caller.
    void set_faults(std::shared_ptr<SimDeviceFaults> faults) { faults_ = std::move(faults); }
    /// The scene it looks at now (with the block's current placement).
    const SceneConfig& scene_config() const { return scene_; }
    /// The scene it looks at, built on first use.
    Expected<std::shared_ptr<const SimWorld>> world();

protected:
    explicit SimScanner(SimScannerParts parts);

    /// The start of every capture: kDisconnected when closed or unplugged, else the world.
    Expected<std::shared_ptr<const SimWorld>> begin_capture();
    /// The device went away during a capture: every later capture fails.
    void set_unplugged() { unplugged_ = true; }
    /// Fills id, sequence, device id and kind, sensor origin (0), the true pose and the
    /// settings; counts the capture.
    void stamp(Scan& scan, const Pose& T_world_scan);
    /// The scan as the injected output faults deliver it (garbage points, a frozen repeat).
    Scan with_output_faults(Scan scan);
    const SceneConfig& scene() const { return scene_; }
    const std::shared_ptr<SimDeviceFaults>& faults() const { return faults_; }
    std::int64_t sequence() const { return sequence_; }

private:
    drivers::DeviceInfo info_;
    drivers::Capabilities caps_;
    drivers::DeviceSettings settings_;
    SceneConfig scene_;
    std::shared_ptr<SimWorldCache> worlds_;
    std::shared_ptr<SimDeviceFaults> faults_;
    std::shared_ptr<const SimWorld> world_;
    std::optional<Scan> last_delivered_;  ///< Kept only while faults are injected.
    std::int64_t sequence_ = 0;
    bool closed_ = false;
    bool unplugged_ = false;
};

}  // namespace anascan::sim
