#pragma once
/// \file
/// Fault injection for the simulated devices, so that tests and demos can drive the error
/// paths a real device takes: unplugged in the middle of a capture, falling silent.

#include <atomic>

namespace anascan::sim {

/// Shared between a test and the device it opened. Thread-safe (atomics).
struct SimDeviceFaults {
    /// Captures that still complete before the device goes away in the middle of the next
    /// one (which then fails with kDisconnected, as every later call does); -1: never.
    std::atomic<int> unplug_after_captures{-1};
    /// While set, a capture delivers nothing and ends with kTimeout (or kCancelled).
    std::atomic<bool> stalled{false};
};

}  // namespace anascan::sim
