#pragma once
// The driver conformance suite runs the same tests over every backend that can run here.
// A backend takes part through one ConformanceHarness: it sets up the device (a mocked
// node, a recording, a folder, a simulated device), opens it, and can make it go away or
// fall silent. To add a backend (e.g. the simulated devices of sim/), implement a harness
// and add one line to conformance_harnesses() in conformance_harnesses.cpp.

#include <functional>
#include <memory>
#include <string>
#include <vector>

#include "anascan/drivers/device.hpp"

namespace anascan::drivers::test {

class ConformanceHarness {
public:
    virtual ~ConformanceHarness() = default;
    /// Opens the device under test (each test makes a new harness).
    virtual Expected<std::unique_ptr<Device>> open() = 0;
    /// Settings the device must accept (every field present must read back).
    virtual DeviceSettings valid_settings() const = 0;
    /// Settings the device must reject with kInvalidArgument.
    virtual DeviceSettings invalid_settings() const = 0;
    /// Call before open(): after `captures` more frames or scans the device goes away.
    virtual void unplug_after(int captures) = 0;
    /// Makes the device stop delivering (frames or scans time out); false when the backend
    /// cannot (a file never stalls), and the timeout test is skipped.
    virtual bool stall() = 0;
    /// Call before open(): every `every`-th frame (1: all) is garbage, as a bad cable or a
    /// confused firmware delivers it; false when the backend cannot (a file is what it is).
    virtual bool garble(int every) {
        (void)every;
        return false;
    }
    /// From now on every frame repeats the last one bit for bit (a frozen camera); false
    /// when the backend cannot.
    virtual bool freeze() { return false; }
    /// What "the device went away" is for this backend: kDisconnected for hardware, kEmpty
    /// for the end of a recording or of a folder of exports.
    virtual ErrorCode gone_code() const { return ErrorCode::kDisconnected; }
};

struct HarnessEntry {
    std::string name;  ///< gtest parameter name: letters, digits, underscores.
    std::function<std::unique_ptr<ConformanceHarness>()> make;
    bool needs_umockdev = false;  ///< Skipped unless run under umockdev-wrapper.
};

/// Every backend in the suite.
std::vector<HarnessEntry> conformance_harnesses();

}  // namespace anascan::drivers::test
