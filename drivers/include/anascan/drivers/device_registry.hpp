#pragma once
/// \file
/// Backends chosen at run time by the scheme of a device URI (`v4l2:`, `usb:`, `ptx:`,
/// `playback:`, and `sim:` once the sim module adds its backend). No call site names a
/// backend type: it asks the registry.

#include <functional>
#include <memory>
#include <string>
#include <string_view>
#include <vector>

#include "anascan/drivers/device.hpp"
#include "anascan/drivers/device_uri.hpp"

namespace anascan::drivers {

/// One device family.
struct Backend {
    std::string scheme;       ///< URI scheme it opens, e.g. "v4l2".
    std::string description;  ///< One line for `anascan devices --help`.
    /// Devices present now (may be empty: folders and recordings are not enumerable).
    std::function<std::vector<DeviceInfo>()> enumerate;
    /// Opens `uri` (its scheme is this backend's).
    std::function<Expected<std::unique_ptr<Device>>(const DeviceUri& uri)> open;
};

/// Scheme → backend. Not thread-safe for add(); the const functions may run concurrently.
class DeviceRegistry {
public:
    /// kInvalidArgument when the scheme is already registered or a function is empty.
    Expected<void> add(Backend backend);
    /// Every device of every backend, in registration order.
    std::vector<DeviceInfo> enumerate() const;
    /// Parses `uri` and opens it with its backend; kUnsupported for an unknown scheme
    /// (the message lists the known ones).
    Expected<std::unique_ptr<Device>> open(std::string_view uri) const;
    const std::vector<Backend>& backends() const { return backends_; }

private:
    std::vector<Backend> backends_;
};

/// The backends of real hardware and files: v4l2, usb, ptx, playback. The composition root
/// (the `anascan` executable) adds the simulated ones of the sim module.
DeviceRegistry make_hardware_registry();

}  // namespace anascan::drivers
