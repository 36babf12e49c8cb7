// `anascan devices` run as a user runs it, with a mocked V4L2 camera and USB device in
// this process's umockdev test bed (the child inherits UMOCKDEV_DIR and the preload, and
// its ioctls are answered by this process).
#include <gtest/gtest.h>
#include <sys/wait.h>

#include <array>
#include <cstdio>
#include <nlohmann/json.hpp>
#include <sstream>
#include <string>
#include <thread>

#include "mock_usb_camera.hpp"
#include "mock_v4l2_camera.hpp"

namespace anascan::drivers::test {
namespace {

struct CliRun {
    int exit_code = -1;
    std::string out;
};

CliRun run_cli(const std::string& args) {
    CliRun run;
    FILE* pipe = ::popen((std::string(ANASCAN_CLI) + " " + args + " 2>&1").c_str(), "r");
    if (pipe == nullptr) return run;
    std::array<char, 4096> buffer{};
    while (std::fgets(buffer.data(), buffer.size(), pipe) != nullptr) run.out += buffer.data();
    const int status = ::pclose(pipe);
    run.exit_code = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
    return run;
}

class DevicesCommand : public ::testing::Test {
protected:
    void SetUp() override {
        if (!umockdev_preloaded()) GTEST_SKIP() << "run under umockdev-wrapper (LD_PRELOAD)";
        v4l2_ = std::make_unique<MockV4l2Camera>(testbed_, MockV4l2Config{.node = "video2"});
        usb_ = std::make_unique<MockUsbCamera>(testbed_, MockUsbConfig{});
    }
    Testbed testbed_;
    std::unique_ptr<MockV4l2Camera> v4l2_;
    std::unique_ptr<MockUsbCamera> usb_;
};

TEST_F(DevicesCommand, ListsCamerasWithCapabilitiesAsJson) {
    const CliRun run = run_cli("devices --json");
    ASSERT_EQ(run.exit_code, 0) << run.out;
    const auto j = nlohmann::json::parse(run.out, nullptr, false);
    ASSERT_TRUE(j.is_array()) << run.out;
    ASSERT_EQ(j.size(), 4u) << run.out;  // the two mocked devices, then the simulated ones
    EXPECT_EQ(j[0]["uri"], "v4l2:/dev/video2");
    EXPECT_EQ(j[0]["model"], "anascan mock depth camera");
    EXPECT_EQ(j[0]["capabilities"]["streams"].size(), 8u);  // 4 formats x 2 rates
    EXPECT_EQ(j[0]["capabilities"]["exposure_us"][1], 100000.0);
    EXPECT_EQ(j[1]["uri"], "usb:1209:0001");
    EXPECT_EQ(j[1]["kind"], "time-of-flight");
    EXPECT_EQ(j[2]["uri"], "sim:tof");
    EXPECT_EQ(j[2]["capabilities"]["angular_step_deg"][0], 0.02);
    EXPECT_EQ(j[3]["uri"], "sim:structured-light");
    EXPECT_EQ(j[3]["kind"], "structured-light");
}

TEST_F(DevicesCommand, PrintsUnitsAndReportsDevicesThatCannotOpen) {
    const CliRun run = run_cli("devices");
    ASSERT_EQ(run.exit_code, 0) << run.out;
    EXPECT_NE(run.out.find("v4l2:/dev/video2"), std::string::npos) << run.out;
    EXPECT_NE(run.out.find("stream: 16 x 12 px z16 at 30 Hz"), std::string::npos) << run.out;
    EXPECT_NE(run.out.find("exposure: 100 to 100000 us"), std::string::npos) << run.out;
    EXPECT_NE(run.out.find("angular step: 0.02 to 5 deg"), std::string::npos) << run.out;
    v4l2_->unplug_now();
    const CliRun gone = run_cli("devices v4l2:/dev/video2");
    EXPECT_EQ(gone.exit_code, 1) << gone.out;
    EXPECT_NE(gone.out.find("/dev/video2"), std::string::npos) << gone.out;
}

// The camera is unplugged once both mocked arrivals are printed (the simulated devices
// arrive too, and stay); the watch lasts long enough for the removal to be seen on a
// loaded machine (polled every 0.2 s).
TEST_F(DevicesCommand, WatchPrintsArrivalsAndRemovals) {
    FILE* pipe = ::popen((std::string(ANASCAN_CLI) + " devices --watch 4 --json").c_str(), "r");
    ASSERT_NE(pipe, nullptr);
    std::vector<nlohmann::json> events;
    std::array<char, 4096> line{};
    while (std::fgets(line.data(), line.size(), pipe) != nullptr) {
        const auto event = nlohmann::json::parse(line.data(), nullptr, false);
        if (event.is_object() && event.value("uri", "").starts_with("sim:")) continue;
        events.push_back(event);
        if (events.size() == 2) v4l2_->unplug_now();
    }
    ASSERT_EQ(::pclose(pipe), 0);
    ASSERT_EQ(events.size(), 3u);
    EXPECT_EQ(events[0]["event"], "arrived");
    EXPECT_EQ(events[1]["event"], "arrived");
    EXPECT_EQ(events[2]["event"], "removed");
    EXPECT_EQ(events[2]["uri"], "v4l2:/dev/video2");
}

}  // namespace
}  // namespace anascan::drivers::test
