#include "scripted_camera.hpp"

#include <thread>

#include "mock_pixel.hpp"

namespace anascan::drivers::test {
namespace {

class ScriptedCamera final : public Camera {
public:
    explicit ScriptedCamera(ScriptedCameraConfig c) : config_(std::move(c)) {
        info_ = DeviceInfo{.uri = "test:scripted", .model = "scripted camera", .is_camera = true};
        const StreamProfile p{config_.width, config_.height, config_.format, 30.0};
        caps_ = Capabilities{
            .can_stream = true, .profiles = {p}, .exposure_us = NumericRange{10, 1000}};
        settings_ = DeviceSettings{.profile = p, .exposure_us = 100.0};
    }
    const DeviceInfo& info() const override { return info_; }
    const Capabilities& capabilities() const override { return caps_; }
    DeviceSettings settings() const override { return settings_; }
    std::string calibration_json() const override { return config_.calibration_json; }
    Expected<void> configure(const DeviceSettings& r) override {
        if (auto ok = validate_settings(r, caps_, info_.uri); !ok) return ok;
        settings_ = merge_settings(settings_, r);
        return {};
    }
    void close() override { closed_ = true; }
    Expected<void> start_stream() override {
        if (closed_) return fail(ErrorCode::kDisconnected, "test:scripted: closed");
        return {};
    }
    Expected<Frame> next_frame(std::chrono::milliseconds timeout) override {
        if (config_.silent) {
            std::this_thread::sleep_for(timeout);
            return fail(ErrorCode::kTimeout, "test:scripted: silent");
        }
        if (closed_ || sequence_ == static_cast<std::uint64_t>(config_.unplug_after_frames)) {
            return fail(ErrorCode::kDisconnected, "test:scripted: unplugged");
        }
        Frame f{.width = config_.width,
                .height = config_.height,
                .format = config_.format,
                .stride_bytes = config_.width * bytes_per_pixel(config_.format),
                .sequence = sequence_};
        for (int r = 0; r < f.height; ++r) {
            for (int c = 0; c < f.width; ++c) {
                const std::uint16_t v = mock_pixel(r, c, sequence_);
                f.data.push_back(static_cast<std::uint8_t>(v & 0xFF));
                if (bytes_per_pixel(f.format) == 2)
                    f.data.push_back(static_cast<std::uint8_t>(v >> 8));
            }
        }
        ++sequence_;
        return f;
    }
    void stop_stream() override {}

private:
    ScriptedCameraConfig config_;
    DeviceInfo info_;
    Capabilities caps_;
    DeviceSettings settings_;
    std::uint64_t sequence_ = 0;
    bool closed_ = false;
};

}  // namespace

std::unique_ptr<Camera> make_scripted_camera(const ScriptedCameraConfig& config) {
    return std::make_unique<ScriptedCamera>(config);
}

}  // namespace anascan::drivers::test
