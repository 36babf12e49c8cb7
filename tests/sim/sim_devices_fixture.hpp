#pragma once
// A small simulated sim:tof for tests: small-block meshed at 10 mm (built once per
// process and kept), a 2-degree sweep (41 x 180 rays), injected faults.

#include <memory>

#include "anascan/sim/sim_tof_scanner.hpp"

namespace anascan::sim::test {

/// The small scene of every sim device test, built once and kept for the process.
inline SceneConfig test_scene() {
    SceneConfig scene = *named_scene("small-block");
    scene.block.grid_step_m = 0.01;
    return scene;
}

inline std::shared_ptr<SimWorldCache> test_worlds() {
    static const auto worlds = std::make_shared<SimWorldCache>();
    static const auto pinned = worlds->get(test_scene());  // keeps the world alive
    return worlds;
}

inline SimTofScannerConfig small_tof_config(std::shared_ptr<SimDeviceFaults> faults = {}) {
    return {.uri = "sim:tof/small-block",
            .scene = test_scene(),
            .scanner = {.angular_step_deg = 2.0},
            .worlds = test_worlds(),
            .faults = std::move(faults)};
}

}  // namespace anascan::sim::test
