#pragma once
// The parts every simulated scanner's config gives its SimScanner base.

#include <string>

#include "anascan/sim/sim_scanner.hpp"

namespace anascan::sim::detail {

/// `Config` has uri, scene, worlds and faults (SimTofScannerConfig,
/// SimStructuredLightConfig); the model is completed with the scene's name.
template <class Config>
SimScannerParts scanner_parts(const Config& c, const std::string& model, DeviceKind kind,
                              drivers::Capabilities caps, drivers::DeviceSettings settings) {
    SimScannerParts parts;
    parts.info.uri = c.uri;
    parts.info.model = model + " (scene " + c.scene.name + ")";
    parts.info.serial = "sim";
    parts.info.kind = kind;
    parts.info.is_scanner = true;
    parts.caps = std::move(caps);
    parts.settings = std::move(settings);
    parts.scene = c.scene;
    parts.worlds = c.worlds;
    parts.faults = c.faults;
    return parts;
}

}  // namespace anascan::sim::detail
