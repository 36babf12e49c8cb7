// Driver conformance: the same behaviour from every backend that can run here (mocked
// V4L2 and USB under umockdev, the ToF depth scanner, playback, PTX stations; sim/'s
// devices in anascan_sim_device_tests, see tests/sim/sim_conformance_harnesses.cpp):
// open → configure → capture → close, unplug in the middle of a capture, timeouts, invalid
// settings, unreadable and frozen frames, no leaked descriptors.
#include <gtest/gtest.h>

#include <filesystem>
#include <thread>

#include "anascan/drivers/camera.hpp"
#include "anascan/drivers/scanner.hpp"
#include "anascan/drivers/stream_runner.hpp"
#include "conformance_harness.hpp"
#include "preload_check.hpp"
#include "stream_until_error.hpp"

namespace anascan::drivers::test {
namespace {

using std::chrono::milliseconds;

std::size_t open_descriptors() {
    std::size_t n = 0;
    for ([[maybe_unused]] const auto& e : std::filesystem::directory_iterator("/proc/self/fd")) ++n;
    return n;
}

/// umockdev closes its side of a socket on its worker thread: allow it a moment.
bool descriptors_back_to(std::size_t baseline) {
    for (int i = 0; i < 200 && open_descriptors() > baseline; ++i)
        std::this_thread::sleep_for(milliseconds(10));
    return open_descriptors() <= baseline;
}

/// One frame or one scan.
Expected<void> capture_once(Device& device, milliseconds timeout) {
    if (Scanner* s = device.as_scanner()) {
        auto scan = s->capture_scan({.timeout = timeout});
        if (!scan) return fail(scan.error());
        if (scan->cloud.empty()) return fail(ErrorCode::kEmpty, "empty scan");
        return {};
    }
    Camera* c = device.as_camera();
    auto frame = c->next_frame(timeout);
    if (!frame) return fail(frame.error());
    return check_frame(*frame, device.info().uri);
}

}  // namespace

void PrintTo(const HarnessEntry& entry, std::ostream* os) { *os << entry.name; }

namespace {

class Conformance : public ::testing::TestWithParam<HarnessEntry> {
protected:
    void SetUp() override {
        if (GetParam().needs_umockdev && !umockdev_preloaded())
            GTEST_SKIP() << "run under umockdev-wrapper (LD_PRELOAD)";
        harness_ = GetParam().make();
        // Libraries initialise some things once per process on first use (GLib's wake-up
        // descriptor, for one): open once before any descriptor count is taken.
        if (auto warm_up = harness_->open()) (*warm_up)->close();
    }
    std::unique_ptr<Device> open() {
        auto device = harness_->open();
        EXPECT_TRUE(device) << device.error().message;
        return device ? std::move(*device) : nullptr;
    }
    void start(Device& d) {
        if (Camera* c = d.as_camera()) {
            ASSERT_TRUE(c->start_stream());
        }
    }
    std::unique_ptr<ConformanceHarness> harness_;
};

TEST_P(Conformance, OpenConfigureCaptureClose) {
    const std::size_t baseline = open_descriptors();
    {
        auto device = open();
        ASSERT_TRUE(device);
        EXPECT_FALSE(device->info().uri.empty());
        EXPECT_TRUE(device->as_camera() || device->as_scanner());
        EXPECT_EQ(device->as_camera() != nullptr, device->capabilities().can_stream);
        EXPECT_EQ(device->as_scanner() != nullptr, device->capabilities().can_capture_scan);
        const DeviceSettings wanted = harness_->valid_settings();
        auto ok = device->configure(wanted);
        ASSERT_TRUE(ok) << ok.error().message;
        EXPECT_EQ(merge_settings(device->settings(), wanted), device->settings());
        start(*device);
        for (int i = 0; i < 3; ++i) {
            auto got = capture_once(*device, milliseconds(2000));
            ASSERT_TRUE(got) << "capture " << i << ": " << got.error().message;
        }
        if (Camera* c = device->as_camera()) c->stop_stream();
        device->close();
        device->close();  // idempotent
        auto after = device->configure(wanted);
        ASSERT_FALSE(after) << "configure after close succeeded";
        EXPECT_EQ(after.error().code, ErrorCode::kDisconnected);
    }
    EXPECT_TRUE(descriptors_back_to(baseline))
        << open_descriptors() << " descriptors, " << baseline << " before";
}

TEST_P(Conformance, InvalidSettingsAreTypedAndChangeNothing) {
    auto device = open();
    ASSERT_TRUE(device);
    const DeviceSettings before = device->settings();
    auto bad = device->configure(harness_->invalid_settings());
    ASSERT_FALSE(bad);
    EXPECT_EQ(bad.error().code, ErrorCode::kInvalidArgument);
    EXPECT_NE(bad.error().message.find(device->info().uri), std::string::npos)
        << bad.error().message;
    EXPECT_EQ(device->settings(), before);
    start(*device);
    EXPECT_TRUE(capture_once(*device, milliseconds(2000)));  // still usable
}

TEST_P(Conformance, UnplugInTheMiddleEndsCleanly) {
    const std::size_t baseline = open_descriptors();
    harness_->unplug_after(2);
    {
        auto device = open();
        ASSERT_TRUE(device);
        if (Scanner* s = device->as_scanner()) {
            EXPECT_TRUE(capture_once(*device, milliseconds(2000)));
            EXPECT_TRUE(capture_once(*device, milliseconds(2000)));
            auto gone = s->capture_scan({.timeout = milliseconds(2000)});
            ASSERT_FALSE(gone);
            EXPECT_EQ(gone.error().code, harness_->gone_code()) << gone.error().message;
        } else {
            const StreamEnd end = stream_until_error(*device->as_camera(), std::chrono::seconds(20),
                                                     {.frame_timeout = milliseconds(2000)});
            ASSERT_TRUE(end.started) << end.error->message;
            ASSERT_TRUE(end.error) << "the stream did not end after the unplug";
            EXPECT_EQ(end.error->code, harness_->gone_code()) << end.error->message;
            EXPECT_EQ(end.frames, 2u);
        }
        device->close();
    }
    EXPECT_TRUE(descriptors_back_to(baseline))
        << open_descriptors() << " descriptors, " << baseline << " before";
}

TEST_P(Conformance, SilenceIsATimeout) {
    auto device = open();
    ASSERT_TRUE(device);
    start(*device);
    ASSERT_TRUE(capture_once(*device, milliseconds(2000)));
    if (!harness_->stall()) GTEST_SKIP() << GetParam().name << " cannot fall silent";
    auto none = capture_once(*device, milliseconds(30));
    ASSERT_FALSE(none);
    EXPECT_EQ(none.error().code, ErrorCode::kTimeout) << none.error().message;
}

TEST_P(Conformance, DestroyingAStreamingDeviceReleasesEverything) {
    const std::size_t baseline = open_descriptors();
    {
        auto device = open();
        ASSERT_TRUE(device);
        start(*device);
        ASSERT_TRUE(capture_once(*device, milliseconds(2000)));
    }  // no stop, no close
    EXPECT_TRUE(descriptors_back_to(baseline))
        << open_descriptors() << " descriptors, " << baseline << " before";
}

bool names(const Error& e, const Device& d) {
    return e.message.find(d.info().uri) != std::string::npos;
}

TEST_P(Conformance, AnUnreadableFrameIsDroppedAndTheDeviceGoesOn) {
    if (!harness_->garble(3)) GTEST_SKIP() << GetParam().name << " cannot deliver garbage";
    auto device = open();
    ASSERT_TRUE(device);
    if (device->as_scanner()) {
        for (int i = 0; i < 3; ++i) {  // each scan waits past the garbled frames
            auto got = capture_once(*device, milliseconds(2000));
            ASSERT_TRUE(got) << "scan " << i << ": " << got.error().message;
        }
        return;
    }
    const StreamEnd end = stream_until_error(*device->as_camera(), std::chrono::seconds(20),
                                             {.frame_timeout = milliseconds(2000)}, {}, 6);
    ASSERT_TRUE(end.started);
    EXPECT_FALSE(end.error) << end.error->message;
    EXPECT_GE(end.frames, 6u);
    EXPECT_GE(end.dropped, 2u);
    ASSERT_FALSE(end.warnings.empty());
    EXPECT_EQ(end.warnings[0].code, ErrorCode::kFormat);
    EXPECT_TRUE(names(end.warnings[0], *device)) << end.warnings[0].message;
}

TEST_P(Conformance, OnlyGarbageEndsWithTheDeviceNamed) {
    if (!harness_->garble(1)) GTEST_SKIP() << GetParam().name << " cannot deliver garbage";
    auto device = open();
    ASSERT_TRUE(device);
    if (Scanner* s = device->as_scanner()) {
        auto scan = s->capture_scan({.timeout = milliseconds(300)});
        ASSERT_FALSE(scan);
        EXPECT_EQ(scan.error().code, ErrorCode::kFormat) << scan.error().message;
        EXPECT_TRUE(names(scan.error(), *device)) << scan.error().message;
        return;
    }
    const StreamEnd end =
        stream_until_error(*device->as_camera(), std::chrono::seconds(20),
                           {.frame_timeout = milliseconds(2000), .max_consecutive_bad_frames = 5});
    ASSERT_TRUE(end.error) << "the stream of garbage did not end";
    EXPECT_EQ(end.error->code, ErrorCode::kFormat) << end.error->message;
    EXPECT_TRUE(names(*end.error, *device)) << end.error->message;
    EXPECT_NE(end.error->message.find("5 unreadable frames in a row"), std::string::npos)
        << end.error->message;
    EXPECT_EQ(end.frames, 0u);
}

TEST_P(Conformance, AFrozenCameraIsReportedAndKeepsStreaming) {
    auto device = open();
    ASSERT_TRUE(device);
    Camera* camera = device->as_camera();
    if (!camera) GTEST_SKIP() << "a scanner's repeated scans are the capture session's check";
    if (!harness_->freeze()) GTEST_SKIP() << GetParam().name << " cannot freeze";
    const StreamEnd end = stream_until_error(
        *camera, std::chrono::seconds(20),
        {.frame_timeout = milliseconds(2000), .identical_frames_warning = 5}, {}, 8);
    EXPECT_FALSE(end.error) << end.error->message;
    EXPECT_GE(end.frames, 8u);
    ASSERT_EQ(end.warnings.size(), 1u) << "one warning per run of identical frames";
    EXPECT_TRUE(names(end.warnings[0], *device)) << end.warnings[0].message;
    EXPECT_NE(end.warnings[0].message.find("identical"), std::string::npos);
}

INSTANTIATE_TEST_SUITE_P(Backends, Conformance, ::testing::ValuesIn(conformance_harnesses()),
                         [](const ::testing::TestParamInfo<HarnessEntry>& p) {
                             return p.param.name;
                         });

}  // namespace
}  // namespace anascan::drivers::test
