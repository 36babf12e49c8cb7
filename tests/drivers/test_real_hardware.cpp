// Real devices attached to this machine (label hw: never in CI). Every camera the hardware
// registry finds is opened, streams a few frames and closes; skipped when none is attached.
#include <gtest/gtest.h>

#include "anascan/drivers/camera.hpp"
#include "anascan/drivers/device_registry.hpp"

namespace anascan::drivers {
namespace {

TEST(RealHardware, EveryAttachedCameraStreams) {
    const DeviceRegistry registry = make_hardware_registry();
    const std::vector<DeviceInfo> devices = registry.enumerate();
    if (devices.empty()) GTEST_SKIP() << "no V4L2 camera or supported USB device attached";
    for (const DeviceInfo& info : devices) {
        auto device = registry.open(info.uri);
        ASSERT_TRUE(device) << device.error().message;
        Camera* camera = (*device)->as_camera();
        if (camera == nullptr) continue;
        ASSERT_TRUE(camera->start_stream()) << info.uri;
        for (int i = 0; i < 5; ++i) {
            auto frame = camera->next_frame(std::chrono::milliseconds(3000));
            ASSERT_TRUE(frame) << frame.error().message;
            EXPECT_TRUE(check_frame(*frame, info.uri));
        }
        camera->stop_stream();
        (*device)->close();
    }
}

}  // namespace
}  // namespace anascan::drivers
