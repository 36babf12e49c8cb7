#pragma once
// Small simulated devices for tests: small-block meshed at 10 mm (built once per
// process and kept), a 2-degree sweep (41 x 180 rays), injected faults.

#include <memory>

#include "anascan/sim/sim_structured_light_scanner.hpp"
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

/// The rig scaled by 0.1: 160 x 120 cameras (3.7 mm per pixel at 1 m), 128 x 80 projector.
inline SimStructuredLightConfig small_sl_config(std::shared_ptr<SimDeviceFaults> faults = {}) {
    return {.uri = "sim:structured-light/small-block",
            .scene = test_scene(),
            .rig = {.camera_width_px = 160,
                    .camera_height_px = 120,
                    .camera_focal_px = 270.0,
                    .projector_width_px = 128,
                    .projector_height_px = 80,
                    .projector_focal_px = 170.0},
            .worlds = test_worlds(),
            .faults = std::move(faults)};
}

}  // namespace anascan::sim::test
