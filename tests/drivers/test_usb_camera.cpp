// The libusb transport, discovery, hotplug and the bulk-frame camera against a scripted
// usbfs device under umockdev (run by umockdev-wrapper).
#include <gtest/gtest.h>

#include "anascan/drivers/stream_runner.hpp"
#include "anascan/drivers/usb_devices.hpp"
#include "event_log.hpp"
#include "mock_usb_camera.hpp"
#include "mock_v4l2_camera.hpp"
#include "stream_until_error.hpp"

namespace anascan::drivers::test {
namespace {

class UsbTest : public ::testing::Test {
protected:
    void SetUp() override {
        if (!umockdev_preloaded()) GTEST_SKIP() << "run under umockdev-wrapper (LD_PRELOAD)";
        mock_ = std::make_unique<MockUsbCamera>(testbed_, MockUsbConfig{});
        registry_.add(make_usb_backend());
    }
    std::unique_ptr<Device> open() {
        auto device = registry_.open(mock_->uri());
        EXPECT_TRUE(device) << device.error().message;
        return device ? std::move(*device) : nullptr;
    }

    Testbed testbed_;
    std::unique_ptr<MockUsbCamera> mock_;
    DeviceRegistry registry_;
};

TEST_F(UsbTest, DiscoversSupportedDevicesOnly) {
    MockUsbCamera other(testbed_, {.vendor_id = 0x046d, .product_id = 0xc52b, .address = 3});
    const std::vector<DeviceInfo> found = enumerate_usb_devices();
    ASSERT_EQ(found.size(), 1u);
    EXPECT_EQ(found[0].uri, "usb:1209:0001");
    EXPECT_EQ(found[0].serial, "bus 1 address 2");
    EXPECT_TRUE(found[0].is_camera);
}

TEST_F(UsbTest, StreamsFramesOverBulkTransfers) {
    auto device = open();
    ASSERT_TRUE(device);
    Camera* camera = device->as_camera();
    ASSERT_NE(camera, nullptr);
    ASSERT_TRUE(camera->configure({.exposure_us = 3000.0}));
    EXPECT_EQ(mock_->exposure_units(), 30);
    ASSERT_TRUE(camera->start_stream());
    EXPECT_TRUE(mock_->streaming());
    for (std::uint64_t i = 0; i < 3; ++i) {
        auto frame = camera->next_frame(std::chrono::milliseconds(1000));
        ASSERT_TRUE(frame) << frame.error().message;
        EXPECT_EQ(frame->sequence, i);
        EXPECT_EQ(frame->format, PixelFormat::kZ16);
        EXPECT_EQ(frame->z16_at(5, 7), mock_pixel(5, 7, i));
    }
    camera->stop_stream();
    EXPECT_FALSE(mock_->streaming());
}

TEST_F(UsbTest, BulkTimeoutIsReportedAndRecoverable) {
    auto device = open();
    ASSERT_TRUE(device);
    Camera* camera = device->as_camera();
    ASSERT_TRUE(camera->start_stream());
    mock_->set_stalled(true);
    auto none = camera->next_frame(std::chrono::milliseconds(50));
    ASSERT_FALSE(none);
    EXPECT_EQ(none.error().code, ErrorCode::kTimeout);
    EXPECT_NE(none.error().message.find("usb:1209:0001"), std::string::npos);
    mock_->set_stalled(false);
    auto frame = camera->next_frame(std::chrono::milliseconds(1000));
    EXPECT_TRUE(frame) << frame.error().message;
}

TEST_F(UsbTest, UnplugDuringStreamingEndsWithDisconnected) {
    auto device = open();
    ASSERT_TRUE(device);
    mock_->unplug_after(4);
    const StreamEnd end = stream_until_error(*device->as_camera(), std::chrono::seconds(10));
    ASSERT_TRUE(end.started);
    ASSERT_TRUE(end.error) << "no error reported after the unplug";
    EXPECT_EQ(end.error->code, ErrorCode::kDisconnected) << end.error->message;
    EXPECT_EQ(end.frames, 4u);
    device->close();
}

TEST_F(UsbTest, UnknownAndAbsentDevicesAreClassified) {
    auto unknown = registry_.open("usb:dead:beef");
    ASSERT_FALSE(unknown);
    EXPECT_EQ(unknown.error().code, ErrorCode::kUnsupported);
    mock_->unplug_now();
    auto absent = registry_.open("usb:1209:0001");
    ASSERT_FALSE(absent);
    EXPECT_EQ(absent.error().code, ErrorCode::kDisconnected);
}

TEST_F(UsbTest, HotplugReportsArrivalAndRemoval) {
    EventLog log;
    auto watcher = UsbHotplugWatcher::start(log.recorder(), std::chrono::milliseconds(20));
    ASSERT_TRUE(watcher);
    ASSERT_TRUE(log.wait_for(1));
    mock_->unplug_now();
    ASSERT_TRUE(log.wait_for(2)) << "no removal event (libusb hotplug: "
                                 << (*watcher)->uses_libusb_hotplug() << ")";
    const std::vector<DeviceEvent> events = log.events();
    EXPECT_EQ(events[0].type, DeviceEventType::kArrived);
    EXPECT_EQ(events[0].device.uri, "usb:1209:0001");
    EXPECT_EQ(events[1].type, DeviceEventType::kRemoved);
}

}  // namespace
}  // namespace anascan::drivers::test
