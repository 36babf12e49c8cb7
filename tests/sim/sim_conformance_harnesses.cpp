// The simulated devices in the driver conformance suite (tests/drivers/test_conformance.cpp
// is built into this executable): "unplugged" and "silent" are injected faults.
#include "conformance_harness.hpp"
#include "sim_devices_fixture.hpp"

namespace anascan::drivers::test {
namespace {

class SimTofHarness : public ConformanceHarness {
public:
    Expected<std::unique_ptr<Device>> open() override {
        return std::unique_ptr<Device>(
            sim::SimTofScanner::open(sim::test::small_tof_config(faults_)));
    }
    DeviceSettings valid_settings() const override {
        return {.angular_step_deg = 2.5, .min_range_m = 2.5, .max_range_m = 100.0};
    }
    DeviceSettings invalid_settings() const override { return {.angular_step_deg = 0.001}; }
    void unplug_after(int captures) override { faults_->unplug_after_captures = captures; }
    bool stall() override {
        faults_->stalled = true;
        return true;
    }

protected:
    std::shared_ptr<sim::SimDeviceFaults> faults_ = std::make_shared<sim::SimDeviceFaults>();
};

class SimStructuredLightHarness : public SimTofHarness {
public:
    Expected<std::unique_ptr<Device>> open() override {
        return std::unique_ptr<Device>(
            sim::SimStructuredLightScanner::open(sim::test::small_sl_config(faults_)));
    }
    DeviceSettings valid_settings() const override {
        return {.exposure_us = 12000.0, .min_range_m = 0.6, .max_range_m = 2.0};
    }
    DeviceSettings invalid_settings() const override { return {.angular_step_deg = 0.5}; }
};

}  // namespace

std::vector<HarnessEntry> conformance_harnesses() {
    return {
        {"sim_tof", [] { return std::make_unique<SimTofHarness>(); }, false},
        {"sim_structured_light", [] { return std::make_unique<SimStructuredLightHarness>(); },
         false},
    };
}

}  // namespace anascan::drivers::test
