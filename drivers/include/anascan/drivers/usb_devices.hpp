#pragma once
/// \file
/// USB hardware the device layer supports (a VID:PID table), its discovery and hotplug,
/// and the `usb:` backend.

#include <cstdint>
#include <functional>
#include <memory>
#include <span>

#include "anascan/drivers/device_registry.hpp"
#include "anascan/drivers/device_watcher.hpp"
#include "anascan/drivers/settings.hpp"

namespace anascan::drivers {

/// One supported product. The protocol decides which Device class opens it.
struct SupportedUsbDevice {
    std::uint16_t vendor_id = 0;
    std::uint16_t product_id = 0;
    const char* model = "";
    DeviceKind kind = DeviceKind::kUnknown;
    StreamProfile profile;  ///< The stream it delivers (bulk-frame protocol).
};

/// The table. The bulk-frame protocol (usb_bulk_camera.hpp) is the only one implemented;
/// it runs on the pid.codes test ID 1209:0001 in the tests. Real products are new rows.
std::span<const SupportedUsbDevice> supported_usb_devices();

/// The row for VID:PID, or nullptr.
const SupportedUsbDevice* find_supported_usb_device(std::uint16_t vendor_id,
                                                    std::uint16_t product_id);

/// Attached devices that are in the table (through libusb; empty when libusb cannot start).
std::vector<DeviceInfo> enumerate_usb_devices();

/// Arrival and removal of supported USB devices: libusb hotplug when the platform offers
/// it, else polling. Events come on the watcher's own thread. Thread-safe to destroy.
class UsbHotplugWatcher {
public:
    static Expected<std::unique_ptr<UsbHotplugWatcher>> start(
        std::function<void(const DeviceEvent&)> on_event,
        std::chrono::milliseconds poll_period = std::chrono::milliseconds(500));
    virtual ~UsbHotplugWatcher() = default;
    /// True when libusb hotplug callbacks are used (false: polling).
    virtual bool uses_libusb_hotplug() const = 0;
};

/// The `usb:` backend.
Backend make_usb_backend();

}  // namespace anascan::drivers
