// The structured-light scanner on its real code paths: the `sl:` URI through the hardware
// registry, the GLFW projector window full screen under a virtual X server (xvfb-run) and
// two V4L2 cameras under umockdev. Each camera frame is what the camera "sees": the mock
// reads the X screen, recognises the pattern on it and serves the recorded image of that
// pattern (rendered once by the simulator). Frames come one call late, as from a driver's
// queue, so after every switch the first frame is from before it: the scanner must drop
// it, and the cloud must be exactly the one decoded from the recording directly.
#include <gtest/gtest.h>

#include <algorithm>
#include <cstdlib>
#include <filesystem>
#include <mutex>
#include <string>
#include <unordered_map>

#include "anascan/acquisition/capture/capture_session.hpp"
#include "anascan/drivers/structured_light_scanner.hpp"
#include "anascan/sim/structured_light_renderer.hpp"
#include "mock_v4l2_camera.hpp"
#include "sim_devices_fixture.hpp"
#include "temp_folder.hpp"
#include "umockdev_testbed.hpp"
#include "x_screen.hpp"

namespace anascan::sim::test {
namespace {

using drivers::test::MockV4l2Camera;

/// The recorded sequence: the small test rig's rendering of the small block.
StructuredLightCapture record(const StructuredLightRig& rig,
                              const StructuredLightRenderConfig& render) {
    auto world = test_worlds()->get(test_scene());
    EXPECT_TRUE(world);
    auto capture = render_structured_light((*world)->caster, (*world)->albedos, rig, render);
    EXPECT_TRUE(capture) << capture.error().message;
    return capture ? std::move(*capture) : StructuredLightCapture{};
}

/// Serves, for whatever pattern the X screen shows, the recorded image of `camera`.
class ScreenWatcher {
public:
    ScreenWatcher(const std::vector<cv::Mat>& patterns, int w, int h) : w_(w), h_(h) {
        for (std::size_t i = 0; i < patterns.size(); ++i)
            index_[std::string(patterns[i].datastart, patterns[i].dataend)] = i;
    }
    /// Index of the pattern on screen; -1 when it shows none of them.
    int pattern_on_screen() const {
        const drivers::Pattern screen = drivers::test::screen_from_x_server(w_, h_);
        const auto it = index_.find(std::string(screen.grey.begin(), screen.grey.end()));
        return it == index_.end() ? -1 : static_cast<int>(it->second);
    }

private:
    int w_, h_;
    std::unordered_map<std::string, std::size_t> index_;
};

std::vector<std::uint8_t> bytes_of(const std::vector<cv::Mat>& images, int index) {
    if (index < 0) return std::vector<std::uint8_t>(images.front().total(), 0);
    return {images[index].datastart, images[index].dataend};
}

class StructuredLightRealParts : public ::testing::Test {
protected:
    void SetUp() override {
        if (!drivers::test::umockdev_preloaded()) GTEST_SKIP() << "run under umockdev-wrapper";
        if (std::getenv("DISPLAY") == nullptr) GTEST_SKIP() << "no DISPLAY: run under xvfb-run";
        const SimStructuredLightConfig sim = small_sl_config();
        rig_ = SimStructuredLightScanner::open(sim)->rig();
        render_ = sim.render;
        render_.patterns.width_px = rig_.projector.width_px;
        render_.patterns.height_px = rig_.projector.height_px;
        recorded_ = record(rig_, render_);
        ASSERT_FALSE(recorded_.cam1.empty());
        patterns_ = drivers::sl::make_patterns(decoder_sequence(render_.patterns));
        screen_ = std::make_unique<ScreenWatcher>(patterns_, rig_.projector.width_px,
                                                  rig_.projector.height_px);
        cam1_ = camera("video0", recorded_.cam1);
        cam2_ = camera("video1", recorded_.cam2);
        ASSERT_TRUE(write_stereo_calibration(calibration(), rig_));
        auto device = drivers::make_hardware_registry().open(uri());
        if (!device && device.error().code == ErrorCode::kUnsupported)
            GTEST_SKIP() << device.error().message;
        ASSERT_TRUE(device) << device.error().message;
        device_ = std::move(*device);
        scanner_ = dynamic_cast<drivers::StructuredLightScanner*>(device_.get());
        ASSERT_NE(scanner_, nullptr);
    }
    std::unique_ptr<MockV4l2Camera> camera(const char* node, const std::vector<cv::Mat>& images) {
        return std::make_unique<MockV4l2Camera>(
            bed_,
            drivers::test::MockV4l2Config{
                .node = node,
                .card = "anascan mock SL camera",
                .width = rig_.cam1.width_px,
                .height = rig_.cam1.height_px,
                .formats = {drivers::PixelFormat::kGrey8},
                .can_read = false,  // user pointers: frames carry driver time stamps
                .frame_source =
                    [this, &images] { return bytes_of(images, screen_->pattern_on_screen()); },
                .one_frame_late = true});
    }
    std::filesystem::path calibration() const { return folder_.path() / "calibration.yml"; }
    std::string uri() const {
        return "sl:" + calibration().string() +
               "?cam1=v4l2:/dev/video0&cam2=v4l2:/dev/video1&projector=0" +
               "&phase_steps=" + std::to_string(render_.patterns.phase_steps) +
               "&phase_period_px=" + std::to_string(render_.patterns.phase_period_px);
    }
    /// Oracle: the recording decoded directly, with the same calibration file and rules.
    PointCloud direct_decode() const {
        auto loaded = drivers::sl::load_stereo_calibration(calibration(), {});
        EXPECT_TRUE(loaded);
        drivers::sl::StereoDecodeConfig config = scanner_->parts().decode;
        config.triangulation.min_depth_m = *scanner_->settings().min_range_m;
        config.triangulation.max_depth_m = *scanner_->settings().max_range_m;
        auto direct = drivers::sl::decode_stereo(recorded_.cam1, recorded_.cam2, *loaded, config);
        EXPECT_TRUE(direct) << direct.error().message;
        return direct ? std::move(direct->cloud) : PointCloud{};
    }

    StructuredLightRig rig_;
    StructuredLightRenderConfig render_;
    StructuredLightCapture recorded_;
    std::vector<cv::Mat> patterns_;
    std::unique_ptr<ScreenWatcher> screen_;
    drivers::test::Testbed bed_;
    drivers::test::TempFolder folder_;
    std::unique_ptr<MockV4l2Camera> cam1_, cam2_;
    std::unique_ptr<drivers::Device> device_;
    drivers::StructuredLightScanner* scanner_ = nullptr;
};

TEST_F(StructuredLightRealParts, ProjectorWindowAndV4l2CamerasGiveTheRecordedCloud) {
    auto scan = scanner_->capture_scan({.timeout = std::chrono::seconds(60)});
    ASSERT_TRUE(scan) << scan.error().message;
    const auto& stats = scanner_->last_capture();
    EXPECT_EQ(stats.patterns_shown, patterns_.size());
    EXPECT_GE(stats.stale_frames, 2 * (patterns_.size() - 1));  // every switch, both cameras

    const PointCloud direct = direct_decode();
    std::printf(
        "sl: (GLFW window + 2 umockdev V4L2 cameras): %zu points, %zu stale frames "
        "dropped; direct decode %zu points\n",
        scan->cloud.size(), stats.stale_frames, direct.size());
    EXPECT_GT(scan->cloud.size(), 5000u);
    ASSERT_EQ(scan->cloud.size(), direct.size());
    EXPECT_EQ(scan->cloud.positions, direct.positions);
    device_->close();
}

// A camera that sends garbage now and then (every 5th frame of cam1 cut in half): a capture
// session drops those frames, takes the scan from good ones (exactly the recorded cloud),
// acknowledges it, and says so once, naming the camera, in its events and its log.
TEST_F(StructuredLightRealParts, GarbledFramesAreDroppedWithAWarningAndTheScanIsTheRecordedOne) {
    const PointCloud direct = direct_decode();
    device_->close();
    device_.reset();
    cam1_->set_garbled(5);
    auto store = acquisition::SessionStore::open(folder_.path() / "session",
                                                 acquisition::SessionOpenMode::kCreateOrOpen);
    ASSERT_TRUE(store) << store.error().message;
    std::mutex mutex;
    std::vector<acquisition::SessionEvent> events;
    auto session = acquisition::CaptureSession::start(
        std::move(*store), {.register_live = false, .coverage_live = false},
        [&](const acquisition::SessionEvent& e) {
            std::lock_guard lock(mutex);
            events.push_back(e);
        });
    ASSERT_TRUE(session) << session.error().message;
    const std::string sl_uri = uri();
    ASSERT_TRUE((*session)->attach_scanner(
        sl_uri, [sl_uri]() -> Expected<std::unique_ptr<drivers::Scanner>> {
            auto device = drivers::make_hardware_registry().open(sl_uri);
            if (!device) return fail(device.error());
            auto* scanner = (*device)->as_scanner();
            if (scanner == nullptr) return fail(ErrorCode::kUnsupported, "not a scanner");
            (void)device->release();
            return std::unique_ptr<drivers::Scanner>(scanner);
        }));
    const auto acknowledged = (*session)->capture({}).get();
    ASSERT_TRUE(acknowledged) << acknowledged.error().message;
    (*session)->wait_until_idle();
    auto saved = (*session)->store().load_scan(*acknowledged);
    ASSERT_TRUE(saved) << saved.error().message;
    EXPECT_EQ(saved->cloud.positions, direct.positions);
    auto log = (*session)->store().events();
    ASSERT_TRUE(log);
    std::vector<std::string> warnings;
    for (const auto& e : *log)
        if (e.kind == "device-warning") warnings.push_back(e.message);
    ASSERT_EQ(warnings.size(), 1u);
    EXPECT_NE(warnings[0].find("unreadable camera frame(s) dropped"), std::string::npos);
    EXPECT_NE(warnings[0].find("cam1 (v4l2:/dev/video0)"), std::string::npos) << warnings[0];
    std::lock_guard lock(mutex);
    EXPECT_EQ(std::count_if(events.begin(), events.end(),
                            [](const auto& e) {
                                return e.kind == acquisition::SessionEventKind::kDeviceWarning;
                            }),
              1);
}

// A V4L2 camera falling silent is a timeout naming it; unplugged in the middle of the
// patterns (ENODEV), the scanner is gone, cleanly.
TEST_F(StructuredLightRealParts, SilentThenUnpluggedCameraAreTypedErrorsNamingIt) {
    cam2_->set_stalled(true);
    auto silent = scanner_->capture_scan({.timeout = std::chrono::milliseconds(400)});
    ASSERT_FALSE(silent);
    EXPECT_EQ(silent.error().code, ErrorCode::kTimeout);
    EXPECT_NE(silent.error().message.find("cam2 (v4l2:/dev/video1)"), std::string::npos)
        << silent.error().message;
    cam2_->set_stalled(false);
    cam2_->unplug_after(20);
    auto gone = scanner_->capture_scan({.timeout = std::chrono::seconds(60)});
    ASSERT_FALSE(gone);
    EXPECT_EQ(gone.error().code, ErrorCode::kDisconnected) << gone.error().message;
    EXPECT_NE(gone.error().message.find("cam2 (v4l2:/dev/video1)"), std::string::npos)
        << gone.error().message;
    EXPECT_LT(scanner_->last_capture().patterns_shown, patterns_.size());
    auto later = scanner_->capture_scan({});
    ASSERT_FALSE(later);
    EXPECT_EQ(later.error().code, ErrorCode::kDisconnected);
    device_->close();
}

}  // namespace
}  // namespace anascan::sim::test
