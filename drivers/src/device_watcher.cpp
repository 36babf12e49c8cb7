#include "anascan/drivers/device_watcher.hpp"

#include <algorithm>

namespace anascan::drivers {
namespace {

bool has_uri(const std::vector<DeviceInfo>& list, const std::string& uri) {
    return std::any_of(list.begin(), list.end(), [&](const DeviceInfo& d) { return d.uri == uri; });
}

}  // namespace

std::vector<DeviceEvent> diff_devices(const std::vector<DeviceInfo>& before,
                                      const std::vector<DeviceInfo>& after) {
    std::vector<DeviceEvent> events;
    for (const DeviceInfo& d : before)
        if (!has_uri(after, d.uri)) events.push_back({DeviceEventType::kRemoved, d});
    for (const DeviceInfo& d : after)
        if (!has_uri(before, d.uri)) events.push_back({DeviceEventType::kArrived, d});
    return events;
}

DeviceWatcher::DeviceWatcher(const DeviceRegistry& registry,
                             std::function<void(const DeviceEvent&)> on_event,
                             std::chrono::milliseconds period)
    : registry_(registry), on_event_(std::move(on_event)), period_(period) {
    thread_ = std::jthread([this](std::stop_token stop) { run(stop); });
}

DeviceWatcher::~DeviceWatcher() { stop(); }

void DeviceWatcher::stop() {
    if (!thread_.joinable()) return;
    thread_.request_stop();
    thread_.join();
}

void DeviceWatcher::run(std::stop_token stop) {
    std::vector<DeviceInfo> known;
    while (!stop.stop_requested()) {
        std::vector<DeviceInfo> now = registry_.enumerate();
        for (const DeviceEvent& e : diff_devices(known, now)) on_event_(e);
        known = std::move(now);
        std::unique_lock lock(mutex_);
        wake_.wait_for(lock, stop, period_, [] { return false; });
    }
}

}  // namespace anascan::drivers
