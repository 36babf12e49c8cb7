#pragma once
// One capture of a simulated scanner: progress, cancel, timeout and the injected faults,
// shared by sim:tof and sim:structured-light.

#include <chrono>
#include <memory>
#include <string>
#include <string_view>

#include "anascan/drivers/scanner.hpp"
#include "anascan/sim/sim_device_faults.hpp"

namespace anascan::sim::detail {

/// Takes one capture (or frame, or pattern) from the fault budget: true when the device is
/// to go away during this one. Thread-safe; null faults: never.
bool take_from_budget(SimDeviceFaults* faults);

/// Not thread-safe: lives on the capturing thread.
class SimCaptureRun {
public:
    /// Takes one capture from the fault budget: when the device is to go away during this
    /// capture, keep_going() stops it half-way with kDisconnected.
    SimCaptureRun(const drivers::CaptureControl& control, std::string uri,
                  const std::shared_ptr<SimDeviceFaults>& faults);

    /// Reports progress; false when the capture must end (stop, timeout, unplug, stall).
    bool keep_going(double fraction, std::string_view stage);
    /// Why keep_going() returned false.
    Error stop_reason() const;
    /// True when this capture unplugged the device (it stays gone).
    bool unplugged() const { return unplugged_; }

private:
    const drivers::CaptureControl& control_;
    std::string uri_;
    std::shared_ptr<SimDeviceFaults> faults_;
    std::chrono::steady_clock::time_point deadline_;
    bool unplug_midway_ = false;
    bool unplugged_ = false;
    ErrorCode reason_ = ErrorCode::kCancelled;
};

}  // namespace anascan::sim::detail
