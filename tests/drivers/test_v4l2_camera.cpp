// The V4L2 backend against a scripted device under umockdev (run by umockdev-wrapper).
#include <gtest/gtest.h>

#include "anascan/drivers/device_watcher.hpp"
#include "anascan/drivers/scanner.hpp"
#include "anascan/drivers/stream_runner.hpp"
#include "anascan/drivers/v4l2_camera.hpp"
#include "event_log.hpp"
#include "mock_v4l2_camera.hpp"
#include "stream_until_error.hpp"

namespace anascan::drivers::test {
namespace {

class V4l2Test : public ::testing::Test {
protected:
    void SetUp() override {
        if (!umockdev_preloaded()) GTEST_SKIP() << "run under umockdev-wrapper (LD_PRELOAD)";
        mock_ = std::make_unique<MockV4l2Camera>(testbed_, MockV4l2Config{});
    }
    std::unique_ptr<Camera> open(V4l2IoMethod io = V4l2IoMethod::kAuto) {
        auto camera = open_v4l2_camera({.device_path = mock_->dev_path(), .io = io});
        EXPECT_TRUE(camera) << camera.error().message;
        return camera ? std::move(*camera) : nullptr;
    }
    void expect_frame_matches(const Frame& f, std::uint64_t sequence) {
        ASSERT_EQ(f.width, 16);
        ASSERT_EQ(f.height, 12);
        for (int r = 0; r < f.height; ++r)
            for (int c = 0; c < f.width; ++c)
                ASSERT_EQ(f.z16_at(r, c), mock_pixel(r, c, sequence)) << r << "," << c;
    }

    Testbed testbed_;
    std::unique_ptr<MockV4l2Camera> mock_;
};

TEST_F(V4l2Test, ReportsModelProfilesAndExposureRange) {
    auto camera = open();
    ASSERT_TRUE(camera);
    EXPECT_EQ(camera->info().model, "anascan mock depth camera");
    EXPECT_EQ(camera->info().uri, mock_->uri());
    EXPECT_EQ(camera->info().kind, DeviceKind::kTimeOfFlight);  // it offers Z16 depth
    const Capabilities& caps = camera->capabilities();
    EXPECT_TRUE(caps.can_stream);
    ASSERT_EQ(caps.profiles.size(), 8u);  // 4 formats x 2 frame rates
    EXPECT_EQ(caps.profiles[0], (StreamProfile{16, 12, PixelFormat::kZ16, 30.0}));
    EXPECT_EQ(caps.profiles[1], (StreamProfile{16, 12, PixelFormat::kZ16, 15.0}));
    ASSERT_TRUE(caps.exposure_us);
    EXPECT_DOUBLE_EQ(caps.exposure_us->min, 100.0);
    EXPECT_DOUBLE_EQ(caps.exposure_us->max, 100000.0);
    EXPECT_DOUBLE_EQ(camera->settings().exposure_us.value_or(0), 10000.0);
}

TEST_F(V4l2Test, EnumeratesSysfsAndSeesRemoval) {
    auto before = enumerate_v4l2_cameras();
    ASSERT_EQ(before.size(), 1u);
    EXPECT_EQ(before[0].uri, mock_->uri());
    EXPECT_EQ(before[0].model, "anascan mock depth camera");
    mock_->unplug_now();
    EXPECT_TRUE(enumerate_v4l2_cameras().empty());
}

TEST_F(V4l2Test, StreamsZ16DepthWithRead) {
    auto camera = open(V4l2IoMethod::kRead);
    ASSERT_TRUE(camera);
    ASSERT_TRUE(camera->configure({.profile = StreamProfile{16, 12, PixelFormat::kZ16}}));
    ASSERT_TRUE(camera->start_stream());
    for (std::uint64_t i = 0; i < 3; ++i) {
        auto frame = camera->next_frame(std::chrono::milliseconds(500));
        ASSERT_TRUE(frame) << frame.error().message;
        EXPECT_EQ(frame->sequence, i);
        expect_frame_matches(*frame, i);
    }
    camera->stop_stream();
}

TEST_F(V4l2Test, StreamsZ16DepthWithUserPointers) {
    auto camera = open(V4l2IoMethod::kUserPointer);
    ASSERT_TRUE(camera);
    ASSERT_TRUE(camera->start_stream());
    EXPECT_EQ(mock_->streamon_count(), 1);
    EXPECT_EQ(mock_->queued_buffers(), 4);
    for (std::uint64_t i = 0; i < 6; ++i) {  // more frames than buffers: each is re-queued
        auto frame = camera->next_frame(std::chrono::milliseconds(500));
        ASSERT_TRUE(frame) << frame.error().message;
        expect_frame_matches(*frame, i);
    }
    EXPECT_EQ(mock_->queued_buffers(), 4);
    camera->stop_stream();
}

TEST_F(V4l2Test, DeliversGreyYuyvAndMjpeg) {
    auto camera = open(V4l2IoMethod::kRead);
    ASSERT_TRUE(camera);
    for (PixelFormat format : {PixelFormat::kGrey8, PixelFormat::kYuyv, PixelFormat::kMjpeg}) {
        ASSERT_TRUE(camera->configure({.profile = StreamProfile{16, 12, format}}));
        ASSERT_TRUE(camera->start_stream());
        auto frame = camera->next_frame(std::chrono::milliseconds(500));
        ASSERT_TRUE(frame) << to_string(format) << ": " << frame.error().message;
        EXPECT_EQ(frame->format, format);
        EXPECT_TRUE(check_frame(*frame, "test")) << to_string(format);
        if (format == PixelFormat::kGrey8) {
            EXPECT_EQ(frame->data[17], mock_pixel(1, 1, mock_->frames_sent() - 1) & 0xFF);
        }
        camera->stop_stream();
    }
}

TEST_F(V4l2Test, SetsTheFrameRate) {
    auto camera = open();
    ASSERT_TRUE(camera);
    EXPECT_DOUBLE_EQ(camera->settings().profile->frame_rate_hz, 30.0);
    ASSERT_TRUE(camera->configure({.profile = StreamProfile{16, 12, PixelFormat::kGrey8, 15.0}}));
    EXPECT_EQ(mock_->frame_rate_hz(), 15);
    EXPECT_EQ(camera->settings().profile, (StreamProfile{16, 12, PixelFormat::kGrey8, 15.0}));
    auto odd = camera->configure({.profile = StreamProfile{16, 12, PixelFormat::kGrey8, 60.0}});
    ASSERT_FALSE(odd);
    EXPECT_EQ(odd.error().code, ErrorCode::kInvalidArgument);
}

TEST_F(V4l2Test, RejectsInvalidSettingsAndKeepsTheOldOnes) {
    auto camera = open();
    ASSERT_TRUE(camera);
    const DeviceSettings before = camera->settings();
    auto too_long = camera->configure({.exposure_us = 5e6});
    ASSERT_FALSE(too_long);
    EXPECT_EQ(too_long.error().code, ErrorCode::kInvalidArgument);
    EXPECT_NE(too_long.error().message.find("exposure_us"), std::string::npos);
    EXPECT_NE(too_long.error().message.find(mock_->uri()), std::string::npos);
    auto odd_size = camera->configure({.profile = StreamProfile{640, 480, PixelFormat::kZ16}});
    ASSERT_FALSE(odd_size);
    EXPECT_EQ(odd_size.error().code, ErrorCode::kInvalidArgument);
    auto no_angle = camera->configure({.angular_step_deg = 0.1});
    ASSERT_FALSE(no_angle);
    EXPECT_EQ(camera->settings(), before);
    ASSERT_TRUE(camera->configure({.exposure_us = 2500.0}));
    EXPECT_DOUBLE_EQ(camera->settings().exposure_us.value_or(0), 2500.0);
}

TEST_F(V4l2Test, BusyDevicesAndConfiguringWhileStreamingAreBusy) {
    auto camera = open(V4l2IoMethod::kUserPointer);
    ASSERT_TRUE(camera);
    mock_->set_busy(true);
    auto taken = camera->configure({.profile = StreamProfile{16, 12, PixelFormat::kGrey8}});
    ASSERT_FALSE(taken);
    EXPECT_EQ(taken.error().code, ErrorCode::kBusy);
    EXPECT_NE(taken.error().message.find("VIDIOC_S_FMT"), std::string::npos);
    auto no_buffers = camera->start_stream();
    ASSERT_FALSE(no_buffers);
    EXPECT_EQ(no_buffers.error().code, ErrorCode::kBusy);
    mock_->set_busy(false);
    ASSERT_TRUE(camera->start_stream());
    auto streaming = camera->configure({.exposure_us = 1000.0});
    ASSERT_FALSE(streaming);
    EXPECT_EQ(streaming.error().code, ErrorCode::kBusy);
}

TEST_F(V4l2Test, TimesOutWhenNoFrameComesThenRecovers) {
    auto camera = open();
    ASSERT_TRUE(camera);
    ASSERT_TRUE(camera->start_stream());
    mock_->set_stalled(true);
    auto none = camera->next_frame(std::chrono::milliseconds(20));
    ASSERT_FALSE(none);
    EXPECT_EQ(none.error().code, ErrorCode::kTimeout);
    EXPECT_NE(none.error().message.find("20 ms"), std::string::npos);
    mock_->set_stalled(false);
    EXPECT_TRUE(camera->next_frame(std::chrono::milliseconds(20)));
}

TEST_F(V4l2Test, UnplugDuringStreamingEndsWithDisconnected) {
    auto camera = open(V4l2IoMethod::kUserPointer);
    ASSERT_TRUE(camera);
    mock_->unplug_after(5);
    const StreamEnd end = stream_until_error(*camera, std::chrono::seconds(10));
    ASSERT_TRUE(end.started);
    ASSERT_TRUE(end.error) << "no error reported after the unplug";
    EXPECT_EQ(end.error->code, ErrorCode::kDisconnected);
    EXPECT_NE(end.error->message.find(mock_->dev_path()), std::string::npos);
    EXPECT_EQ(end.frames, 5u);
    auto after = camera->configure({.exposure_us = 1000.0});
    ASSERT_FALSE(after);
    EXPECT_EQ(after.error().code, ErrorCode::kDisconnected);
    camera->close();
}

TEST_F(V4l2Test, WatcherReportsArrivalAndRemoval) {
    DeviceRegistry registry;
    ASSERT_TRUE(registry.add(make_v4l2_backend()));
    EventLog log;
    DeviceWatcher watcher(registry, log.recorder(), std::chrono::milliseconds(10));
    ASSERT_TRUE(log.wait_for(1));
    mock_->unplug_now();
    ASSERT_TRUE(log.wait_for(2));
    const std::vector<DeviceEvent> events = log.events();
    EXPECT_EQ(events[0].type, DeviceEventType::kArrived);
    EXPECT_EQ(events[0].device.uri, mock_->uri());
    EXPECT_EQ(events[1].type, DeviceEventType::kRemoved);
    EXPECT_EQ(events[1].device.model, "anascan mock depth camera");
}

TEST_F(V4l2Test, MissingNodeIsDisconnectedAndNamed) {
    auto camera = open_v4l2_camera({.device_path = "/dev/video7"});
    ASSERT_FALSE(camera);
    EXPECT_EQ(camera.error().code, ErrorCode::kDisconnected);
    EXPECT_NE(camera.error().message.find("/dev/video7"), std::string::npos);
}

}  // namespace
}  // namespace anascan::drivers::test

namespace anascan::drivers::test {
namespace {

// `depth:CAMERA_URI?intrinsics`: the Z16 camera as a scanner, opened by the registry.
TEST_F(V4l2Test, DepthUriGivesAScannerWithTheIntrinsicsOfTheUri) {
    const DeviceRegistry registry = make_hardware_registry();
    const std::string uri = "depth:" + mock_->uri() + "?fx_px=20&fy_px=20&cx_px=7.5&cy_px=5.5";
    auto device = registry.open(uri);
    ASSERT_TRUE(device) << device.error().message;
    Scanner* scanner = (*device)->as_scanner();
    ASSERT_NE(scanner, nullptr);
    EXPECT_EQ((*device)->info().uri, uri);
    EXPECT_NE((*device)->calibration_json().find("\"fx_px\":20"), std::string::npos);
    auto scan = scanner->capture_scan({.timeout = std::chrono::milliseconds(2000)});
    ASSERT_TRUE(scan) << scan.error().message;
    ASSERT_EQ(scan->cloud.size(), 16u * 12u);
    // Pixel (0, 0) of frame 0: depth mock_pixel mm, x = (0 - cx) z / fx.
    const double z_m = 0.001 * mock_pixel(0, 0, 0);
    EXPECT_NEAR(scan->cloud.positions[0].z(), z_m, 1e-6);
    EXPECT_NEAR(scan->cloud.positions[0].x(), -7.5 * z_m / 20.0, 1e-6);
    auto missing = registry.open("depth:" + mock_->uri() + "?fx_px=20");
    ASSERT_FALSE(missing);
    EXPECT_EQ(missing.error().code, ErrorCode::kInvalidArgument);
    EXPECT_NE(missing.error().message.find("missing fy_px"), std::string::npos)
        << missing.error().message;
    auto unknown = registry.open("depth:" + mock_->uri() + "?fx_px=20&focal=3");
    ASSERT_FALSE(unknown);
    EXPECT_NE(unknown.error().message.find("unknown key 'focal'"), std::string::npos);
}

}  // namespace
}  // namespace anascan::drivers::test
