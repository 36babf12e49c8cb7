#pragma once
// The device registry of the command line: the composition root puts the real backends
// (drivers) and the simulated ones (sim) together.

#include "anascan/drivers/device_registry.hpp"

namespace anascan::cli {

/// v4l2:, usb:, ptx:, playback: and, once the sim module offers them, sim:.
drivers::DeviceRegistry make_cli_registry();

}  // namespace anascan::cli
