#include "anascan/drivers/depth_camera_scanner.hpp"
#include "anascan/drivers/device_registry.hpp"
#include "anascan/drivers/e57_station_scanner.hpp"
#include "anascan/drivers/ptx_station_scanner.hpp"
#include "anascan/drivers/recording.hpp"
#include "anascan/drivers/structured_light_scanner.hpp"
#include "anascan/drivers/usb_devices.hpp"
#include "anascan/drivers/v4l2_camera.hpp"

namespace anascan::drivers {

DeviceRegistry make_hardware_registry() {
    DeviceRegistry registry;
    for (Backend b : {make_v4l2_backend(), make_usb_backend(), make_ptx_backend(),
                      make_e57_backend(), make_playback_backend()}) {
        (void)registry.add(std::move(b));  // distinct schemes: cannot fail
    }
    // The cameras the composed scanners (`sl:`, `depth:`) are made of.
    auto cameras = std::make_shared<DeviceRegistry>();
    for (Backend b : {make_v4l2_backend(), make_usb_backend(), make_playback_backend()})
        (void)cameras->add(std::move(b));
    (void)registry.add(make_structured_light_backend(cameras));
    (void)registry.add(make_depth_scanner_backend(std::move(cameras)));
    return registry;
}

}  // namespace anascan::drivers
