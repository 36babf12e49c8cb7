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

/// The composed head with one part failing: an unplug takes that part away in the middle
/// of a capture, a stall silences it (the projector cannot fall silent here).
class SimSlPartHarness : public SimStructuredLightHarness {
public:
    explicit SimSlPartHarness(sim::SlPart part) : part_(part) {}
    Expected<std::unique_ptr<Device>> open() override {
        auto device = sim::SimStructuredLightScanner::open(sim::test::small_sl_config());
        part_faults_ = device->part_faults(part_);
        if (unplug_after_ >= 0) {
            // Frames (a camera) or patterns (the projector) of whole captures, then half.
            const int n = static_cast<int>(patterns_per_capture());
            part_faults_->unplug_after_captures = unplug_after_ * n + n / 2;
        }
        return std::unique_ptr<Device>(std::move(device));
    }
    void unplug_after(int captures) override { unplug_after_ = captures; }
    bool stall() override {
        if (part_ == sim::SlPart::kProjector) return false;
        part_faults_->stalled = true;
        return true;
    }

private:
    static std::size_t patterns_per_capture() {
        const sim::SimStructuredLightConfig c = sim::test::small_sl_config();
        return sim::decoder_sequence({.width_px = c.rig.projector_width_px,
                                      .height_px = c.rig.projector_height_px,
                                      .phase_steps = c.render.patterns.phase_steps,
                                      .phase_period_px = c.render.patterns.phase_period_px})
            .image_count();
    }
    sim::SlPart part_;
    int unplug_after_ = -1;
    std::shared_ptr<sim::SimDeviceFaults> part_faults_;
};

}  // namespace

std::vector<HarnessEntry> conformance_harnesses() {
    return {
        {"sim_tof", [] { return std::make_unique<SimTofHarness>(); }, false},
        {"sim_structured_light", [] { return std::make_unique<SimStructuredLightHarness>(); },
         false},
        {"sim_sl_cam2", [] { return std::make_unique<SimSlPartHarness>(sim::SlPart::kCam2); },
         false},
        {"sim_sl_projector",
         [] { return std::make_unique<SimSlPartHarness>(sim::SlPart::kProjector); }, false},
    };
}

}  // namespace anascan::drivers::test
