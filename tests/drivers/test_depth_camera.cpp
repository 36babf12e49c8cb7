// Time-of-flight: Z16 depth + intrinsics → oriented point cloud, and the depth scanner.
#include <gtest/gtest.h>

#include <thread>

#include "anascan/drivers/depth_camera_scanner.hpp"
#include "mock_pixel.hpp"
#include "scripted_camera.hpp"

namespace anascan::drivers {
namespace {

Frame plane_frame(int w, int h, std::uint16_t depth_mm) {
    Frame f{.width = w, .height = h, .format = PixelFormat::kZ16, .stride_bytes = 2u * w};
    for (int i = 0; i < w * h; ++i) {
        f.data.push_back(static_cast<std::uint8_t>(depth_mm & 0xFF));
        f.data.push_back(static_cast<std::uint8_t>(depth_mm >> 8));
    }
    return f;
}

TEST(DepthToPointCloud, BackProjectsAFrontoParallelPlane) {
    Frame f = plane_frame(8, 6, 1500);
    f.data[2 * (2 * 8 + 5)] = 0;  // pixel (2, 5): no return
    f.data[2 * (2 * 8 + 5) + 1] = 0;
    const DepthIntrinsics k{.fx_px = 10.0, .fy_px = 12.0, .cx_px = 3.5, .cy_px = 2.5};
    RangeGrid grid;
    auto cloud = depth_to_point_cloud(f, k, &grid);
    ASSERT_TRUE(cloud) << cloud.error().message;
    ASSERT_EQ(cloud->size(), 47u);
    EXPECT_EQ(grid.at(2, 5), RangeGrid::kNoSample);
    const Eigen::Vector3f p = cloud->positions[grid.at(4, 7)];
    EXPECT_NEAR(p.z(), 1.5f, 1e-6f);
    EXPECT_NEAR(p.x(), (7 - 3.5) * 1.5 / 10.0, 1e-6);
    EXPECT_NEAR(p.y(), (4 - 2.5) * 1.5 / 12.0, 1e-6);
    ASSERT_TRUE(cloud->attributes_consistent());
    for (const Eigen::Vector3f& n : cloud->normals)
        EXPECT_NEAR(n.z(), -1.0f, 1e-5f);  // toward sensor
}

TEST(DepthToPointCloud, NormalsOfATiltedPlaneFaceTheSensor) {
    Frame f = plane_frame(10, 10, 0);
    for (int r = 0; r < 10; ++r)
        for (int c = 0; c < 10; ++c) {
            const auto d = static_cast<std::uint16_t>(2000 + 40 * c);  // depth grows to the right
            f.data[2 * (r * 10 + c)] = static_cast<std::uint8_t>(d & 0xFF);
            f.data[2 * (r * 10 + c) + 1] = static_cast<std::uint8_t>(d >> 8);
        }
    auto cloud = depth_to_point_cloud(f, {.fx_px = 20, .fy_px = 20, .cx_px = 4.5, .cy_px = 4.5});
    ASSERT_TRUE(cloud);
    for (std::size_t i = 0; i < cloud->size(); ++i) {
        EXPECT_LT(cloud->normals[i].dot(cloud->positions[i]), 0.0f) << i;
        EXPECT_GT(cloud->normals[i].x(), 0.1f) << i;  // the plane turns toward +x
    }
}

TEST(DepthToPointCloud, RejectsNonDepthFramesAndBadIntrinsics) {
    Frame grey{.width = 2,
               .height = 2,
               .format = PixelFormat::kGrey8,
               .stride_bytes = 2,
               .data = {1, 2, 3, 4}};
    EXPECT_EQ(depth_to_point_cloud(grey, {.fx_px = 1, .fy_px = 1}).error().code,
              ErrorCode::kFormat);
    EXPECT_EQ(depth_to_point_cloud(plane_frame(2, 2, 5), {}).error().code,
              ErrorCode::kInvalidArgument);
}

TEST(DepthCameraScanner, CapturesOneOrientedScanPerCall) {
    auto scanner = make_depth_camera_scanner(
        test::make_scripted_camera(), {.fx_px = 20, .fy_px = 20, .cx_px = 7.5, .cy_px = 5.5});
    EXPECT_TRUE(scanner->info().is_scanner);
    EXPECT_EQ(scanner->info().kind, DeviceKind::kTimeOfFlight);
    for (int i = 0; i < 2; ++i) {
        auto scan = scanner->capture_scan({});
        ASSERT_TRUE(scan) << scan.error().message;
        EXPECT_EQ(scan->cloud.size(), 16u * 12u);
        EXPECT_EQ(scan->meta.sequence, i);
        EXPECT_TRUE(scan->meta.sensor_origin_scan_m);
        EXPECT_NEAR(scan->cloud.positions[0].z(), test::mock_pixel(0, 0, i) * 0.001f, 1e-6f);
        EXPECT_NE(scan->meta.settings_json.find("z16"), std::string::npos);
    }
    EXPECT_NE(scanner->calibration_json().find("\"fx_px\":20"), std::string::npos);
}

TEST(DepthCameraScanner, ReportsTheCameraUnplug) {
    auto scanner = make_depth_camera_scanner(test::make_scripted_camera({.unplug_after_frames = 0}),
                                             {.fx_px = 20, .fy_px = 20});
    auto scan = scanner->capture_scan({});
    ASSERT_FALSE(scan);
    EXPECT_EQ(scan.error().code, ErrorCode::kDisconnected);
}

TEST(DepthCameraScanner, ACancelEndsTheWaitForAFrame) {
    auto scanner = make_depth_camera_scanner(test::make_scripted_camera({.silent = true}),
                                             {.fx_px = 20, .fy_px = 20});
    std::stop_source stop;
    std::thread canceller([&] {
        std::this_thread::sleep_for(std::chrono::milliseconds(50));
        stop.request_stop();
    });
    // With a 60 s timeout, only the cancel can end this call soon (and with kCancelled).
    auto scan =
        scanner->capture_scan({.stop = stop.get_token(), .timeout = std::chrono::seconds(60)});
    canceller.join();
    ASSERT_FALSE(scan);
    EXPECT_EQ(scan.error().code, ErrorCode::kCancelled);
}

TEST(DepthCameraScanner, SilenceIsATimeoutNamingTheDevice) {
    auto scanner = make_depth_camera_scanner(test::make_scripted_camera({.silent = true}),
                                             {.fx_px = 20, .fy_px = 20});
    auto scan = scanner->capture_scan({.timeout = std::chrono::milliseconds(30)});
    ASSERT_FALSE(scan);
    EXPECT_EQ(scan.error().code, ErrorCode::kTimeout);
    EXPECT_NE(scan.error().message.find("test:scripted"), std::string::npos);
}

}  // namespace
}  // namespace anascan::drivers
