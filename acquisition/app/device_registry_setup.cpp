#include "device_registry_setup.hpp"

namespace anascan::cli {

drivers::DeviceRegistry make_cli_registry() {
    drivers::DeviceRegistry registry = drivers::make_hardware_registry();
    // sim/ adds its backend here: (void)registry.add(sim::make_sim_backend());
    return registry;
}

}  // namespace anascan::cli
