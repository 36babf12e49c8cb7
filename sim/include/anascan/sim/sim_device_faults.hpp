#pragma once
/// \file
/// Fault injection for the simulated devices, so that tests and demos can drive the error
/// paths a real device takes: unplugged in the middle of a capture, falling silent, delivering
/// garbage or the same frame again.

#include <atomic>

namespace anascan::sim {

/// Shared between a test and the device it opened. Thread-safe (atomics).
struct SimDeviceFaults {
    /// Captures that still complete before the device goes away in the middle of the next
    /// one (which then fails with kDisconnected, as every later call does); -1: never.
    std::atomic<int> unplug_after_captures{-1};
    /// While set, a capture delivers nothing and ends with kTimeout (or kCancelled).
    std::atomic<bool> stalled{false};
    /// The next N scanners' scans arrive with every point NaN, as from a decoder or firmware
    /// gone wrong (the capture itself succeeds).
    std::atomic<int> garbage_scans{0};
    /// While set, a scanner delivers its previous scan again, unchanged: a frozen camera.
    std::atomic<bool> frozen{false};
};

}  // namespace anascan::sim
