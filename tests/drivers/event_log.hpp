#pragma once
// Collects device events from a watcher's thread; the test thread waits for a count.

#include <chrono>
#include <condition_variable>
#include <mutex>
#include <vector>

#include "anascan/drivers/device_watcher.hpp"

namespace anascan::drivers::test {

/// Thread-safe.
class EventLog {
public:
    /// The callback to hand to a watcher.
    auto recorder() {
        return [this](const DeviceEvent& e) {
            std::lock_guard lock(mutex_);
            events_.push_back(e);
            changed_.notify_all();
        };
    }
    /// Waits until at least `count` events came (false after `limit`); returns a copy.
    bool wait_for(std::size_t count, std::chrono::seconds limit = std::chrono::seconds(10)) {
        std::unique_lock lock(mutex_);
        return changed_.wait_for(lock, limit, [&] { return events_.size() >= count; });
    }
    std::vector<DeviceEvent> events() const {
        std::lock_guard lock(mutex_);
        return events_;
    }

private:
    mutable std::mutex mutex_;
    std::condition_variable changed_;
    std::vector<DeviceEvent> events_;
};

}  // namespace anascan::drivers::test
