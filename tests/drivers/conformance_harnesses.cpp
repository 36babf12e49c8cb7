#include <fstream>

#include "anascan/drivers/depth_camera_scanner.hpp"
#include "anascan/drivers/ptx_station_scanner.hpp"
#include "anascan/drivers/recording.hpp"
#include "anascan/drivers/usb_devices.hpp"
#include "anascan/drivers/v4l2_camera.hpp"
#include "conformance_harness.hpp"
#include "mock_usb_camera.hpp"
#include "mock_v4l2_camera.hpp"
#include "scripted_camera.hpp"
#include "temp_folder.hpp"

namespace anascan::drivers::test {
namespace {

Expected<std::unique_ptr<Device>> as_device(Expected<std::unique_ptr<Camera>> c) {
    if (!c) return fail(c.error());
    return std::unique_ptr<Device>(std::move(*c));
}

/// A umockdev-mocked device: its faults are the mock's (unplug, stall, garbage, frozen).
template <class Mock, class MockConfig>
class MockedHarness : public ConformanceHarness {
public:
    MockedHarness() : mock_(testbed_, MockConfig{}) {}
    void unplug_after(int n) override { mock_.unplug_after(n); }
    bool stall() override {
        mock_.set_stalled(true);
        return true;
    }
    bool garble(int every) override {
        mock_.set_garbled(every);
        return true;
    }
    bool freeze() override {
        mock_.set_frozen(true);
        return true;
    }

protected:
    Testbed testbed_;
    Mock mock_;
};

class V4l2Harness : public MockedHarness<MockV4l2Camera, MockV4l2Config> {
public:
    explicit V4l2Harness(V4l2IoMethod io) : io_(io) {}
    Expected<std::unique_ptr<Device>> open() override {
        return as_device(open_v4l2_camera({.device_path = mock_.dev_path(), .io = io_}));
    }
    DeviceSettings valid_settings() const override {
        return {.profile = StreamProfile{16, 12, PixelFormat::kZ16, 30.0}, .exposure_us = 2500.0};
    }
    DeviceSettings invalid_settings() const override { return {.exposure_us = 5e6}; }

protected:
    V4l2IoMethod io_;
};

/// Time-of-flight: the mocked V4L2 Z16 camera with intrinsics, as a scanner.
class DepthScannerHarness : public V4l2Harness {
public:
    DepthScannerHarness() : V4l2Harness(V4l2IoMethod::kAuto) {}
    Expected<std::unique_ptr<Device>> open() override {
        auto camera = open_v4l2_camera({.device_path = mock_.dev_path()});
        if (!camera) return fail(camera.error());
        return std::unique_ptr<Device>(make_depth_camera_scanner(
            std::move(*camera), {.fx_px = 20, .fy_px = 20, .cx_px = 7.5, .cy_px = 5.5}));
    }
};

class UsbHarness : public MockedHarness<MockUsbCamera, MockUsbConfig> {
public:
    Expected<std::unique_ptr<Device>> open() override {
        auto uri = parse_device_uri(mock_.uri());
        return make_usb_backend().open(*uri);
    }
    DeviceSettings valid_settings() const override { return {.exposure_us = 3000.0}; }
    DeviceSettings invalid_settings() const override {
        return {.profile = StreamProfile{640, 480, PixelFormat::kZ16}};
    }
};

/// A recording of 10 frames; "unplugged" = a recording that ends, cut, after n frames.
class PlaybackHarness : public ConformanceHarness {
public:
    PlaybackHarness() { record(10, false); }
    Expected<std::unique_ptr<Device>> open() override {
        return as_device(open_playback({.folder = folder_.path() / "rec"}));
    }
    DeviceSettings valid_settings() const override { return {.exposure_us = 100.0}; }
    DeviceSettings invalid_settings() const override { return {.exposure_us = -1.0}; }
    void unplug_after(int n) override { record(n, true); }
    bool stall() override { return false; }
    ErrorCode gone_code() const override { return ErrorCode::kEmpty; }

private:
    void record(int frames, bool cut_last) {
        const auto dir = folder_.path() / "rec";
        std::filesystem::remove_all(dir);
        auto camera = record_camera(make_scripted_camera(), {.folder = dir});
        (void)(*camera)->start_stream();
        for (int i = 0; i < frames + (cut_last ? 1 : 0); ++i) (void)(*camera)->next_frame({});
        (*camera)->close();
        if (cut_last) {
            const auto file = dir / "frames.bin";
            std::filesystem::resize_file(file, std::filesystem::file_size(file) - 7);
        }
    }
    TempFolder folder_;
};

/// A folder of station exports; "unplugged" = a folder holding only n stations.
class PtxHarness : public ConformanceHarness {
public:
    PtxHarness() { write(5); }
    Expected<std::unique_ptr<Device>> open() override {
        auto s = open_ptx_station_scanner(folder_.path());
        if (!s) return fail(s.error());
        return std::unique_ptr<Device>(std::move(*s));
    }
    DeviceSettings valid_settings() const override { return {}; }
    DeviceSettings invalid_settings() const override { return {.angular_step_deg = 0.1}; }
    void unplug_after(int n) override { write(n); }
    bool stall() override { return false; }
    ErrorCode gone_code() const override { return ErrorCode::kEmpty; }

private:
    void write(int stations) {
        for (const auto& e : std::filesystem::directory_iterator(folder_.path()))
            std::filesystem::remove(e);
        for (int i = 0; i < stations; ++i) {
            std::ofstream(folder_.path() / ("s" + std::to_string(i) + ".ptx"))
                << "1\n2\n0 0 0\n1 0 0\n0 1 0\n0 0 1\n1 0 0 0\n0 1 0 0\n0 0 1 0\n0 0 0 1\n"
                   "1 2 3 0.5\n1 2 4 0.5\n";
        }
    }
    TempFolder folder_;
};

/// The PTX stations recorded, played back as a scanner; "unplugged" = n recorded scans.
class ScanPlaybackHarness : public ConformanceHarness {
public:
    ScanPlaybackHarness() { record(5); }
    Expected<std::unique_ptr<Device>> open() override {
        return open_playback_device({.folder = folder_.path() / "rec"});
    }
    DeviceSettings valid_settings() const override { return {}; }
    DeviceSettings invalid_settings() const override { return {.exposure_us = 100.0}; }
    void unplug_after(int n) override { record(n); }
    bool stall() override { return false; }
    ErrorCode gone_code() const override { return ErrorCode::kEmpty; }

private:
    void record(int scans) {
        std::filesystem::remove_all(folder_.path());
        std::filesystem::create_directories(folder_.path() / "ptx");
        for (int i = 0; i < scans; ++i)
            std::ofstream(folder_.path() / "ptx" / ("s" + std::to_string(i) + ".ptx"))
                << "1\n2\n0 0 0\n1 0 0\n0 1 0\n0 0 1\n1 0 0 0\n0 1 0 0\n0 0 1 0\n0 0 0 1\n"
                   "1 2 3 0.5\n1 2 4 0.5\n";
        auto ptx = open_ptx_station_scanner(folder_.path() / "ptx");
        auto recorder = record_scanner(std::move(*ptx), {.folder = folder_.path() / "rec"});
        while ((*recorder)->capture_scan({})) {
        }
    }
    TempFolder folder_;
};

}  // namespace

std::vector<HarnessEntry> conformance_harnesses() {
    return {
        {"v4l2_read", [] { return std::make_unique<V4l2Harness>(V4l2IoMethod::kRead); }, true},
        {"v4l2_userptr", [] { return std::make_unique<V4l2Harness>(V4l2IoMethod::kUserPointer); },
         true},
        {"tof_v4l2_z16", [] { return std::make_unique<DepthScannerHarness>(); }, true},
        {"usb_bulk", [] { return std::make_unique<UsbHarness>(); }, true},
        {"playback", [] { return std::make_unique<PlaybackHarness>(); }, false},
        {"ptx_stations", [] { return std::make_unique<PtxHarness>(); }, false},
        {"scan_playback", [] { return std::make_unique<ScanPlaybackHarness>(); }, false},
        // sim/'s devices run this suite in anascan_sim_device_tests, with their harnesses
        // in tests/sim/sim_conformance_harnesses.cpp (drivers' tests do not link sim).
    };
}

}  // namespace anascan::drivers::test
