// The simulated scanners as devices: metadata and true pose, stations, cancel, timeout,
// and the sim: backend of the registry.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <stop_token>
#include <string>
#include <vector>

#include "anascan/drivers/recording.hpp"
#include "anascan/drivers/settings.hpp"
#include "anascan/sim/sim_backend.hpp"
#include "sim_devices_fixture.hpp"
#include "temp_folder.hpp"

namespace anascan::sim::test {
namespace {

using drivers::CaptureControl;
using drivers::CaptureProgress;

TEST(SimTofDevice, ScanCarriesItsTruePoseAndSettings) {
    SimTofScannerConfig config = small_tof_config();
    config.scanner.range_noise_sigma_m = 0.0;  // exact ranges: each point must be on the mesh
    config.scanner.mixed_pixel_probability = 0.0;
    auto device = SimTofScanner::open(config);
    ASSERT_TRUE(device->configure({.angular_step_deg = 3.0, .max_range_m = 50.0}));
    const Pose T_world_station = device->station_pose();
    auto scan = device->capture_scan({});
    ASSERT_TRUE(scan) << scan.error().message;
    ASSERT_GT(scan->cloud.size(), 1000u);
    EXPECT_EQ(scan->meta.device_id, "sim:tof/small-block");
    EXPECT_EQ(scan->meta.device_kind, DeviceKind::kTimeOfFlight);
    ASSERT_TRUE(scan->meta.sensor_origin_scan_m);
    EXPECT_EQ(*scan->meta.sensor_origin_scan_m, Eigen::Vector3d::Zero());
    ASSERT_TRUE(scan->meta.T_world_scan);
    EXPECT_TRUE(scan->meta.T_world_scan->isApprox(T_world_station));
    auto settings = drivers::settings_from_json(scan->meta.settings_json, "scan");
    ASSERT_TRUE(settings) << settings.error().message;
    EXPECT_EQ(*settings, device->settings());
    EXPECT_EQ(settings->angular_step_deg, 3.0);
    // Oracle: a ray from the true sensor position through each point (world frame) meets
    // the scene's mesh at the point's range.
    auto world = device->world();
    ASSERT_TRUE(world);
    std::size_t off = 0;
    for (std::size_t i = 0; i < scan->cloud.size(); i += 7) {
        const Eigen::Vector3d p = scan->cloud.positions[i].cast<double>();
        const Eigen::Vector3d dir = T_world_station.linear() * p.normalized();
        const auto hit = (*world)->caster.cast(T_world_station.translation(), dir);
        if (!hit || std::abs(hit->distance_m - p.norm()) > 1e-4) ++off;
    }
    EXPECT_EQ(off, 0u);
}

// The sweep is a setting: a narrower field gives a smaller grid of the same step, about
// the same elevation centre; outside the LMS-Z420i's 360 x 80 degrees it is refused.
TEST(SimTofDevice, TheSweepFieldIsASetting) {
    auto device = SimTofScanner::open(small_tof_config());
    EXPECT_EQ(device->settings().horizontal_field_deg, 360.0);
    EXPECT_EQ(device->settings().vertical_field_deg, 80.0);
    auto full = device->capture_scan({});
    ASSERT_TRUE(full) << full.error().message;
    ASSERT_TRUE(device->configure({.horizontal_field_deg = 180.0, .vertical_field_deg = 40.0}));
    auto half = device->capture_scan({});
    ASSERT_TRUE(half) << half.error().message;
    auto settings = drivers::settings_from_json(half->meta.settings_json, "scan");
    ASSERT_TRUE(settings);
    EXPECT_EQ(settings->horizontal_field_deg, 180.0);
    // Elevation of the lowest point: the full field reaches -40 degrees, this one -20.
    auto lowest_deg = [](const Scan& scan) {
        double lowest = 90.0;
        for (const Eigen::Vector3f& p : scan.cloud.positions)
            lowest = std::min(lowest,
                              std::atan2(double(p.z()), double(p.head<2>().norm())) * 180.0 / M_PI);
        return lowest;
    };
    EXPECT_LT(lowest_deg(*full), -30.0);
    EXPECT_GE(lowest_deg(*half), -20.0 - 2.0);  // one 2-degree step of slack
    EXPECT_LT(half->cloud.size(), full->cloud.size() * 3 / 4);
    auto bad = device->configure({.vertical_field_deg = 120.0});
    ASSERT_FALSE(bad);
    EXPECT_EQ(bad.error().code, ErrorCode::kInvalidArgument);
    EXPECT_NE(bad.error().message.find("vertical_field_deg"), std::string::npos);
}

TEST(SimTofDevice, EachCaptureIsTheNextStationAndTheBlockCanBeTurnedOver) {
    auto device = SimTofScanner::open(small_tof_config());
    auto first = device->capture_scan({});
    auto second = device->capture_scan({});
    ASSERT_TRUE(first && second);
    EXPECT_EQ(second->meta.sequence, first->meta.sequence + 1);
    EXPECT_NE(first->meta.id, second->meta.id);
    // 90 degrees further around the block, same height and distance.
    const Eigen::Vector3d a = first->meta.T_world_scan->translation();
    const Eigen::Vector3d b = second->meta.T_world_scan->translation();
    EXPECT_NEAR(a.z(), b.z(), 1e-9);
    const Eigen::Vector3d centre = (*device->world())->scene.T_world_block.translation();
    const Eigen::Vector2d da = (a - centre).head<2>(), db = (b - centre).head<2>();
    EXPECT_NEAR(da.norm(), 3.5, 1e-9);
    EXPECT_NEAR(std::atan2(da.x() * db.y() - da.y() * db.x(), da.dot(db)) * 180.0 / M_PI, 90.0,
                1e-6);
    device->move_to({.azimuth_deg = 45.0, .distance_m = 3.0, .height_m = 1.2});
    device->place_block({.resting_face = BlockFace::kPosZ});
    auto turned = device->capture_scan({});
    ASSERT_TRUE(turned) << turned.error().message;
    EXPECT_NEAR(turned->meta.T_world_scan->translation().z(), 1.2, 1e-9);
    auto world = device->world();
    ASSERT_TRUE(world);
    EXPECT_FALSE(world->get()->scene.T_world_block.isApprox(
        block_pose({}, world->get()->scene.block_size_m)));
    EXPECT_TRUE(world->get()->scene.T_world_block.isApprox(
        block_pose({.resting_face = BlockFace::kPosZ}, world->get()->scene.block_size_m)));
}

// A capture session: the recording decorator around the simulated scanner keeps each
// station's true pose, and playback gives the stations back in order.
TEST(SimTofDevice, RecordedStationsPlayBackWithTheirTruePoses) {
    const drivers::test::TempFolder folder;
    auto recorder = drivers::record_scanner(SimTofScanner::open(small_tof_config()),
                                            {.folder = folder.path() / "rec"});
    ASSERT_TRUE(recorder) << recorder.error().message;
    std::vector<Pose> poses;
    for (int i = 0; i < 3; ++i) {
        auto scan = (*recorder)->capture_scan({});
        ASSERT_TRUE(scan) << scan.error().message;
        poses.push_back(*scan->meta.T_world_scan);
    }
    (*recorder)->close();
    auto playback = drivers::open_playback_device({.folder = folder.path() / "rec"});
    ASSERT_TRUE(playback) << playback.error().message;
    for (const Pose& pose : poses) {
        auto scan = (*playback)->as_scanner()->capture_scan({});
        ASSERT_TRUE(scan) << scan.error().message;
        EXPECT_EQ(scan->meta.device_id, "sim:tof/small-block");
        ASSERT_TRUE(scan->meta.T_world_scan);
        EXPECT_TRUE(scan->meta.T_world_scan->isApprox(pose, 1e-9));
    }
    EXPECT_FALSE(poses[0].isApprox(poses[1]));
}

TEST(SimTofDevice, CancelInTheMiddleStopsTheSweepAndTheDeviceStaysUsable) {
    auto device = SimTofScanner::open(small_tof_config());
    std::stop_source stop;
    std::vector<double> fractions;
    auto cancelled = device->capture_scan({.on_progress =
                                               [&](const CaptureProgress& p) {
                                                   fractions.push_back(p.fraction);
                                                   if (p.fraction > 0.3) stop.request_stop();
                                               },
                                           .stop = stop.get_token()});
    ASSERT_FALSE(cancelled);
    EXPECT_EQ(cancelled.error().code, ErrorCode::kCancelled) << cancelled.error().message;
    ASSERT_FALSE(fractions.empty());
    EXPECT_LT(fractions.back(), 0.5);  // it did not sweep on
    fractions.clear();
    auto scan = device->capture_scan(
        {.on_progress = [&](const CaptureProgress& p) { fractions.push_back(p.fraction); }});
    ASSERT_TRUE(scan) << scan.error().message;
    EXPECT_TRUE(std::is_sorted(fractions.begin(), fractions.end()));
    EXPECT_EQ(fractions.back(), 1.0);
}

TEST(SimTofDevice, ATooShortTimeoutIsATimeoutNamingTheDevice) {
    auto device = SimTofScanner::open(small_tof_config());
    auto none = device->capture_scan({.timeout = std::chrono::milliseconds(0)});
    ASSERT_FALSE(none);
    EXPECT_EQ(none.error().code, ErrorCode::kTimeout);
    EXPECT_NE(none.error().message.find("sim:tof/small-block"), std::string::npos);
}

TEST(SimBackend, EnumeratesTheSimulatedScannersAndOpensByUri) {
    drivers::DeviceRegistry registry;
    ASSERT_TRUE(registry.add(make_sim_backend()));
    const auto devices = registry.enumerate();
    ASSERT_EQ(devices.size(), 2u);
    EXPECT_EQ(devices[0].uri, "sim:tof");
    EXPECT_EQ(devices[0].kind, DeviceKind::kTimeOfFlight);
    EXPECT_EQ(devices[1].uri, "sim:structured-light");
    EXPECT_EQ(devices[1].kind, DeviceKind::kStructuredLight);
    EXPECT_TRUE(devices[0].is_scanner && devices[1].is_scanner);
    for (const char* uri :
         {"sim:tof", "sim:tof/small-block-turned", "sim:structured-light/large-block"}) {
        auto device = registry.open(uri);
        ASSERT_TRUE(device) << uri << ": " << device.error().message;
        EXPECT_EQ((*device)->info().uri, uri);
        EXPECT_TRUE((*device)->capabilities().range_m);
        EXPECT_NE((*device)->as_scanner(), nullptr);
    }
    auto model = registry.open("sim:lidar");
    ASSERT_FALSE(model);
    EXPECT_EQ(model.error().code, ErrorCode::kUnsupported);
    EXPECT_NE(model.error().message.find("sim:lidar"), std::string::npos);
    auto scene = registry.open("sim:tof/no-such-scene");
    ASSERT_FALSE(scene);
    EXPECT_EQ(scene.error().code, ErrorCode::kInvalidArgument);
    EXPECT_NE(scene.error().message.find("octagon-block"), std::string::npos)
        << scene.error().message;  // lists the known scenes
}

}  // namespace
}  // namespace anascan::sim::test

namespace anascan::sim::test {
namespace {

TEST(SimStructuredLightDevice, DecodedScanLiesOnTheTrueSurfaceAtItsTruePose) {
    auto device = SimStructuredLightScanner::open(small_sl_config());
    const Pose T_world_cam1 = device->rig().cam1.T_world_device;
    auto scan = device->capture_scan({});
    ASSERT_TRUE(scan) << scan.error().message;
    EXPECT_EQ(scan->meta.device_kind, DeviceKind::kStructuredLight);
    EXPECT_EQ(scan->meta.device_id, "sim:structured-light/small-block");
    ASSERT_TRUE(scan->meta.T_world_scan);
    EXPECT_TRUE(scan->meta.T_world_scan->isApprox(T_world_cam1));
    ASSERT_GT(scan->cloud.size(), 5000u);  // of 19200 camera pixels
    // Oracle: the ray from the true cam1 centre through each point meets the mesh there.
    // At 3.7 mm per camera pixel a pixel of disparity is 9 mm of depth, so the bound is
    // loose; the accuracy at full resolution is measured in test_structured_light.cpp.
    auto world = device->world();
    ASSERT_TRUE(world);
    std::vector<double> errors_m;
    for (const Eigen::Vector3f& p : scan->cloud.positions) {
        const Eigen::Vector3d dir = T_world_cam1.linear() * p.cast<double>().normalized();
        const auto hit = (*world)->caster.cast(T_world_cam1.translation(), dir);
        errors_m.push_back(hit ? std::abs(hit->distance_m - p.cast<double>().norm()) : 1e9);
    }
    std::sort(errors_m.begin(), errors_m.end());
    const double median_mm = 1000.0 * errors_m[errors_m.size() / 2];
    const double p90_mm = 1000.0 * errors_m[errors_m.size() * 9 / 10];
    std::printf(
        "sim:structured-light 160 x 120: %zu points, median %.3f mm, 90 %% within %.3f mm\n",
        scan->cloud.size(), median_mm, p90_mm);
    EXPECT_LT(median_mm, 1.0);
    EXPECT_LT(p90_mm, 3.0);
    // The next capture is from the next viewpoint.
    EXPECT_FALSE(device->rig().cam1.T_world_device.isApprox(T_world_cam1));
}

// The sync rule of drivers::StructuredLightScanner: a frame exposed before its pattern was
// shown is never used. Cameras that deliver one such stale frame after every switch give
// the same scan as cameras that do not.
TEST(SimStructuredLightDevice, StaleFramesAfterAPatternSwitchAreDropped) {
    auto fresh = SimStructuredLightScanner::open(small_sl_config());
    SimStructuredLightConfig queued_config = small_sl_config();
    queued_config.stale_frame_after_switch = true;
    auto queued = SimStructuredLightScanner::open(queued_config);
    auto a = fresh->capture_scan({});
    auto b = queued->capture_scan({});
    ASSERT_TRUE(a) << a.error().message;
    ASSERT_TRUE(b) << b.error().message;
    const std::size_t patterns = fresh->last_capture().patterns_shown;
    EXPECT_EQ(fresh->last_capture().stale_frames, 0u);
    // Each camera: one stale frame per switch after its first frame.
    EXPECT_EQ(queued->last_capture().stale_frames, 2 * (patterns - 1));
    EXPECT_EQ(queued->last_capture().frames_used, 2 * patterns);
    ASSERT_EQ(a->cloud.size(), b->cloud.size());
    EXPECT_EQ(a->cloud.positions, b->cloud.positions);
}

TEST(SimStructuredLightDevice, CancelDuringThePatternsStopsAndTheDeviceStaysUsable) {
    auto device = SimStructuredLightScanner::open(small_sl_config());
    std::stop_source stop;
    std::vector<std::string> stages;
    auto cancelled = device->capture_scan({.on_progress =
                                               [&](const drivers::CaptureProgress& p) {
                                                   stages.push_back(p.stage);
                                                   if (stages.size() == 5) stop.request_stop();
                                               },
                                           .stop = stop.get_token()});
    ASSERT_FALSE(cancelled);
    EXPECT_EQ(cancelled.error().code, ErrorCode::kCancelled) << cancelled.error().message;
    EXPECT_EQ(device->last_capture().patterns_shown, 5u);
    ASSERT_FALSE(stages.empty());
    EXPECT_NE(stages.front().find("projecting pattern 1/"), std::string::npos) << stages.front();
    auto next = device->capture_scan({});
    EXPECT_TRUE(next) << next.error().message;
}

TEST(SimStructuredLightDevice, ASilentCameraIsATimeoutNamingIt) {
    auto device = SimStructuredLightScanner::open(small_sl_config());
    device->part_faults(SlPart::kCam2)->stalled = true;
    // Long enough for cam1's frame under ThreadSanitizer too (it took more than 300 ms).
    auto none = device->capture_scan({.timeout = std::chrono::seconds(3)});
    ASSERT_FALSE(none);
    EXPECT_EQ(none.error().code, ErrorCode::kTimeout);
    EXPECT_NE(none.error().message.find("sim:structured-light/small-block#cam2"), std::string::npos)
        << none.error().message;
    device->part_faults(SlPart::kCam2)->stalled = false;
    auto again = device->capture_scan({});  // a silent camera is not a lost one
    EXPECT_TRUE(again) << again.error().message;
}

TEST(SimStructuredLightDevice, AProjectorGoneMidCaptureIsADisconnectNamingIt) {
    auto device = SimStructuredLightScanner::open(small_sl_config());
    device->part_faults(SlPart::kProjector)->unplug_after_captures = 7;
    auto gone = device->capture_scan({});
    ASSERT_FALSE(gone);
    EXPECT_EQ(gone.error().code, ErrorCode::kDisconnected);
    EXPECT_NE(gone.error().message.find("#projector"), std::string::npos) << gone.error().message;
    EXPECT_EQ(device->last_capture().patterns_shown, 7u);
    auto later = device->capture_scan({});
    ASSERT_FALSE(later);
    EXPECT_EQ(later.error().code, ErrorCode::kDisconnected);
}

}  // namespace
}  // namespace anascan::sim::test
