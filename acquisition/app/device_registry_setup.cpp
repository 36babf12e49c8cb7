#include "device_registry_setup.hpp"

#include "anascan/sim/sim_backend.hpp"

namespace anascan::cli {

drivers::DeviceRegistry make_cli_registry() {
    drivers::DeviceRegistry registry = drivers::make_hardware_registry();
    // The simulated devices of sim/ (sim:tof, sim:structured-light).
    (void)registry.add(sim::make_sim_backend());
    return registry;
}

}  // namespace anascan::cli
