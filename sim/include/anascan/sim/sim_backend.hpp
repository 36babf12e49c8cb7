#pragma once
/// \file
/// The `sim:` scheme of the device registry: the simulated scanners as devices.
/// URIs: `sim:tof` and `sim:structured-light`, each looking at the default scene
/// (octagon-block), or `sim:MODEL/SCENE` for another predefined scene
/// (`sim:tof/small-block-turned`; `anascan sim list-scenes` lists them).

#include <memory>
#include <string_view>

#include "anascan/drivers/device_registry.hpp"
#include "anascan/sim/scene.hpp"
#include "anascan/sim/sim_world.hpp"

namespace anascan::sim {

/// The scene a `sim:` URI names when it names none.
inline constexpr std::string_view kDefaultSimScene = "octagon-block";

/// Opens `sim:tof[/SCENE]` or `sim:structured-light[/SCENE]`; kUnsupported for another
/// model, kInvalidArgument for an unknown scene. Scenes come from `worlds` (shared).
Expected<std::unique_ptr<drivers::Device>> open_sim_device(
    const drivers::DeviceUri& uri, const std::shared_ptr<SimWorldCache>& worlds);

/// What a `sim:` URI names, without opening it (to plan a tour before the capture).
struct SimDeviceTarget {
    bool terrestrial = false;  ///< sim:tof; else sim:structured-light.
    SceneConfig scene;
};

/// kInvalidArgument for a URI that is not `sim:...`, kUnsupported for another model, and
/// an unknown scene's error.
Expected<SimDeviceTarget> sim_device_target(const std::string& uri);

/// Backend{.scheme = "sim"}: enumerate lists sim:tof and sim:structured-light (always
/// present); open builds the scene on first use and shares it between devices.
drivers::Backend make_sim_backend();

}  // namespace anascan::sim
