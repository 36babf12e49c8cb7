// The device model without hardware: settings validation, frames, registry, watcher diff,
// stream runner.
#include <gtest/gtest.h>

#include <atomic>
#include <condition_variable>
#include <mutex>

#include "anascan/drivers/device_registry.hpp"
#include "anascan/drivers/device_watcher.hpp"
#include "anascan/drivers/stream_runner.hpp"
#include "event_log.hpp"
#include "scripted_camera.hpp"

namespace anascan::drivers {
namespace {

Capabilities scanner_caps() {
    return Capabilities{.can_capture_scan = true,
                        .angular_step_deg = NumericRange{0.01, 1.0},
                        .range_m = NumericRange{2.0, 800.0}};
}

TEST(Settings, AcceptsValuesInsideTheRanges) {
    EXPECT_TRUE(
        validate_settings({.angular_step_deg = 0.05, .min_range_m = 2.0, .max_range_m = 300.0},
                          scanner_caps(), "sim:tof"));
}

TEST(Settings, RejectsOutOfRangeMissingAndInconsistentValues) {
    struct Case {
        DeviceSettings settings;
        const char* names;
    } cases[] = {
        {{.angular_step_deg = 2.0}, "angular_step_deg 2 outside [0.01, 1]"},
        {{.max_range_m = 900.0}, "max_range_m 900 outside [2, 800]"},
        {{.exposure_us = 100.0}, "exposure_us 100: the device has no such setting"},
        {{.min_range_m = 50.0, .max_range_m = 10.0}, "min_range_m must be below max_range_m"},
        {{.profile = StreamProfile{640, 480, PixelFormat::kZ16}}, "is not offered"}};
    for (const Case& c : cases) {
        auto ok = validate_settings(c.settings, scanner_caps(), "sim:tof");
        ASSERT_FALSE(ok) << c.names;
        EXPECT_EQ(ok.error().code, ErrorCode::kInvalidArgument);
        EXPECT_NE(ok.error().message.find(c.names), std::string::npos) << ok.error().message;
        EXPECT_EQ(ok.error().message.rfind("sim:tof: ", 0), 0u) << ok.error().message;
    }
}

TEST(Settings, JsonRoundTripKeepsEveryField) {
    const DeviceSettings s{.profile = StreamProfile{640, 480, PixelFormat::kYuyv, 30.0},
                           .exposure_us = 1500.0,
                           .gain = 2.0,
                           .angular_step_deg = 0.1,
                           .min_range_m = 2.0,
                           .max_range_m = 50.0};
    auto back = settings_from_json(settings_to_json(s), "test");
    ASSERT_TRUE(back) << back.error().message;
    EXPECT_EQ(*back, s);
    auto bad = settings_from_json("{\"profile\":{\"width\":1}}", "rec/device.json");
    ASSERT_FALSE(bad);
    EXPECT_EQ(bad.error().code, ErrorCode::kFormat);
    EXPECT_NE(bad.error().message.find("rec/device.json"), std::string::npos);
}

TEST(Frame, ChecksBufferSizesAndJpegMarkers) {
    Frame f{.width = 4, .height = 2, .format = PixelFormat::kZ16, .stride_bytes = 8};
    f.data.assign(16, 0);
    EXPECT_TRUE(check_frame(f, "cam"));
    f.data.resize(15);
    auto short_frame = check_frame(f, "cam");
    ASSERT_FALSE(short_frame);
    EXPECT_NE(short_frame.error().message.find("needs 16 bytes"), std::string::npos);
    Frame jpeg{
        .width = 4, .height = 2, .format = PixelFormat::kMjpeg, .data = {0xFF, 0xD8, 0, 0xFF}};
    EXPECT_TRUE(check_frame(jpeg, "cam"));
    jpeg.data[1] = 0;
    EXPECT_FALSE(check_frame(jpeg, "cam"));
    for (PixelFormat p :
         {PixelFormat::kGrey8, PixelFormat::kYuyv, PixelFormat::kMjpeg, PixelFormat::kZ16})
        EXPECT_EQ(*parse_pixel_format(to_string(p)), p);
    EXPECT_FALSE(parse_pixel_format("rgb24"));
}

Backend fake_backend(std::string scheme, std::vector<DeviceInfo>* present) {
    return Backend{.scheme = scheme,
                   .description = "test",
                   .enumerate = [present] { return *present; },
                   .open = [](const DeviceUri&) -> Expected<std::unique_ptr<Device>> {
                       return std::unique_ptr<Device>(test::make_scripted_camera());
                   }};
}

TEST(Registry, OpensBySchemeAndRejectsUnknownOrDuplicateSchemes) {
    std::vector<DeviceInfo> present{{.uri = "fake:a"}};
    DeviceRegistry registry;
    ASSERT_TRUE(registry.add(fake_backend("fake", &present)));
    EXPECT_FALSE(registry.add(fake_backend("fake", &present)));
    EXPECT_EQ(registry.enumerate(), present);
    auto device = registry.open("fake:anything");
    ASSERT_TRUE(device);
    EXPECT_NE((*device)->as_camera(), nullptr);
    auto unknown = registry.open("nope:x");
    ASSERT_FALSE(unknown);
    EXPECT_EQ(unknown.error().code, ErrorCode::kUnsupported);
    EXPECT_NE(unknown.error().message.find("known: fake:"), std::string::npos);
    EXPECT_EQ(registry.open("garbage").error().code, ErrorCode::kInvalidArgument);
}

TEST(Registry, HardwareRegistryHasTheRealBackends) {
    const DeviceRegistry registry = make_hardware_registry();
    std::vector<std::string> schemes;
    for (const Backend& b : registry.backends()) schemes.push_back(b.scheme);
    EXPECT_EQ(schemes,
              (std::vector<std::string>{"v4l2", "usb", "ptx", "e57", "playback", "sl", "depth"}));
}

// The composed devices' URIs fail clearly before any part is opened.
TEST(Registry, ComposedScannerUrisNameWhatIsWrong) {
    const DeviceRegistry registry = make_hardware_registry();
    auto error_of = [&](const std::string& uri) {
        auto device = registry.open(uri);
        EXPECT_FALSE(device) << uri;
        return device ? Error{} : device.error();
    };
    const Error no_cam2 = error_of("sl:calib.yml?cam1=v4l2:/dev/video2");
    EXPECT_EQ(no_cam2.code, ErrorCode::kInvalidArgument);
    EXPECT_NE(no_cam2.message.find("cam2=URI"), std::string::npos) << no_cam2.message;
    const Error unknown = error_of("sl:calib.yml?cam1=a:1&cam2=b:2&lens=9");
    EXPECT_EQ(unknown.code, ErrorCode::kInvalidArgument);
    EXPECT_NE(unknown.message.find("unknown key 'lens'"), std::string::npos) << unknown.message;
    const Error bad_number = error_of("sl:calib.yml?cam1=a:1&cam2=b:2&phase_steps=four");
    EXPECT_NE(bad_number.message.find("phase_steps=four is not an integer"), std::string::npos)
        << bad_number.message;
    const Error no_file = error_of("sl:/no/such/calib.yml?cam1=a:1&cam2=b:2");
    EXPECT_EQ(no_file.code, ErrorCode::kIo);
    EXPECT_NE(no_file.message.find("/no/such/calib.yml"), std::string::npos) << no_file.message;
    const Error depth = error_of("depth:v4l2:/dev/video9?fx_px=0&fy_px=1&cx_px=1&cy_px=1");
    EXPECT_EQ(depth.code, ErrorCode::kInvalidArgument);
    EXPECT_NE(depth.message.find("must be positive"), std::string::npos) << depth.message;
}

TEST(Watcher, DiffReportsRemovalsThenArrivals) {
    const std::vector<DeviceInfo> before{{.uri = "a:1"}, {.uri = "b:2"}};
    const std::vector<DeviceInfo> after{{.uri = "b:2"}, {.uri = "c:3"}};
    const auto events = diff_devices(before, after);
    ASSERT_EQ(events.size(), 2u);
    EXPECT_EQ(events[0].type, DeviceEventType::kRemoved);
    EXPECT_EQ(events[0].device.uri, "a:1");
    EXPECT_EQ(events[1].type, DeviceEventType::kArrived);
    EXPECT_EQ(events[1].device.uri, "c:3");
}

TEST(Watcher, PollsTheRegistry) {
    std::vector<DeviceInfo> present{{.uri = "fake:a"}};
    DeviceRegistry registry;
    ASSERT_TRUE(registry.add(fake_backend("fake", &present)));
    test::EventLog log;
    DeviceWatcher watcher(registry, log.recorder(), std::chrono::milliseconds(5));
    ASSERT_TRUE(log.wait_for(1));
    watcher.stop();  // the list is read by the watcher thread: change it only when stopped
    EXPECT_EQ(log.events()[0].device.uri, "fake:a");
    EXPECT_EQ(log.events()[0].type, DeviceEventType::kArrived);
}

TEST(StreamRunner, DeliversFramesInOrderThenReportsTheUnplugOnce) {
    auto camera = test::make_scripted_camera({.unplug_after_frames = 7});
    std::mutex m;
    std::condition_variable cv;
    std::vector<std::uint64_t> sequences;
    std::vector<Error> errors;
    auto runner = StreamRunner::start(*camera, {.on_frame =
                                                    [&](const Frame& f) {
                                                        std::lock_guard lock(m);
                                                        sequences.push_back(f.sequence);
                                                    },
                                                .on_error =
                                                    [&](const Error& e) {
                                                        std::lock_guard lock(m);
                                                        errors.push_back(e);
                                                        cv.notify_all();
                                                    }});
    ASSERT_TRUE(runner);
    std::unique_lock lock(m);
    ASSERT_TRUE(cv.wait_for(lock, std::chrono::seconds(10), [&] { return !errors.empty(); }));
    lock.unlock();
    (*runner)->stop();
    EXPECT_EQ(sequences, (std::vector<std::uint64_t>{0, 1, 2, 3, 4, 5, 6}));
    ASSERT_EQ(errors.size(), 1u);
    EXPECT_EQ(errors[0].code, ErrorCode::kDisconnected);
}

}  // namespace
}  // namespace anascan::drivers
