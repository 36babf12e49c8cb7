#pragma once
/// \file
/// Arrival and removal of devices, by comparing enumerations at a fixed period (works for
/// every backend; USB also has libusb hotplug, see usb_hotplug.hpp).

#include <chrono>
#include <condition_variable>
#include <functional>
#include <mutex>
#include <thread>
#include <vector>

#include "anascan/drivers/device_registry.hpp"

namespace anascan::drivers {

enum class DeviceEventType { kArrived, kRemoved };

struct DeviceEvent {
    DeviceEventType type = DeviceEventType::kArrived;
    DeviceInfo device;
};

/// The changes between two enumerations (matched by URI): removed first, then arrived.
std::vector<DeviceEvent> diff_devices(const std::vector<DeviceInfo>& before,
                                      const std::vector<DeviceInfo>& after);

/// Polls `registry.enumerate()` on its own thread and calls `on_event` (on that thread)
/// for each change. Devices present at start are reported as arrivals. Thread-safe: the
/// destructor (or stop()) may be called from any thread but the callback's.
class DeviceWatcher {
public:
    DeviceWatcher(const DeviceRegistry& registry, std::function<void(const DeviceEvent&)> on_event,
                  std::chrono::milliseconds period = std::chrono::milliseconds(500));
    ~DeviceWatcher();
    DeviceWatcher(const DeviceWatcher&) = delete;
    DeviceWatcher& operator=(const DeviceWatcher&) = delete;
    void stop();

private:
    void run(std::stop_token stop);

    const DeviceRegistry& registry_;
    std::function<void(const DeviceEvent&)> on_event_;
    std::chrono::milliseconds period_;
    std::mutex mutex_;
    std::condition_variable_any wake_;
    std::jthread thread_;
};

}  // namespace anascan::drivers
