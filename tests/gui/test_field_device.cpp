// anascan-field's device panel on a live session, under a virtual X server (xvfb-run, Mesa
// llvmpipe): "Connect" reads the simulated scanner's settings and starts the camera
// preview (both structured-light cameras drawn in the panel), settings typed into the panel
// are applied through the capture session, an out-of-range value gets a clear message.
#include <gtest/gtest.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <opencv2/core/mat.hpp>
#include <set>
#include <string>

#include "field_app_run.hpp"
#include "screenshot_png.hpp"

using anascan::field::test::read_screenshot;

namespace fs = std::filesystem;
using nlohmann::json;

namespace {

json read_json(const fs::path& file) {
    std::ifstream in(file);
    return json::parse(in, nullptr, false);
}

const json* applied(const json& state, const std::string& key) {
    for (const json& s : state["device_settings"]["applied"])
        if (s["key"] == key) return &s;
    return nullptr;
}

class FieldDevice : public ::testing::Test {
protected:
    void SetUp() override {
        if (std::getenv("DISPLAY") == nullptr) GTEST_SKIP() << anascan::test::kNoDisplay;
        dir_ = anascan::test::fresh_test_dir("anascan_field_device_");
    }
    void TearDown() override {
        std::error_code ec;
        if (!dir_.empty()) fs::remove_all(dir_, ec);
    }
    anascan::test::RunResult field(const std::string& args) const {
        return anascan::test::run_command(std::string(ANASCAN_FIELD) + " " + args);
    }
    fs::path dir_;
};

TEST_F(FieldDevice, ConnectShowsBothCamerasAndAppliesTypedSettings) {
    const fs::path session = dir_ / "session", png = dir_ / "out.png",
                   state_file = dir_ / "state.json";
    const auto r = field("--session " + session.string() +
                         " --device sim:structured-light/small-block --connect "
                         "--apply-setting exposure_us=20000 --apply-setting max_range_m=2.5 "
                         "--frames 3 --screenshot " +
                         png.string() + " --dump-state " + state_file.string());
    ASSERT_EQ(r.exit_code, 0) << r.output;
    const json state = read_json(state_file);
    ASSERT_TRUE(state.is_object()) << state_file;

    const json& settings = state["device_settings"];
    EXPECT_TRUE(settings["connected"].get<bool>()) << settings.dump(2);
    EXPECT_FALSE(settings["message_is_error"].get<bool>()) << settings.dump(2);
    EXPECT_NE(settings["message"].get<std::string>().find("Applied"), std::string::npos);
    const json* exposure = applied(state, "exposure_us");
    ASSERT_NE(exposure, nullptr) << settings.dump(2);
    EXPECT_EQ((*exposure)["unit"], "µs");
    EXPECT_DOUBLE_EQ((*exposure)["value"].get<double>(), 20000.0) << "as the device reports it";
    const json* far = applied(state, "max_range_m");
    ASSERT_NE(far, nullptr);
    EXPECT_DOUBLE_EQ((*far)["value"].get<double>(), 2.5);

    // The live preview: two camera images, drawn side by side inside the device panel.
    const json& preview = state["camera_preview"];
    ASSERT_EQ(preview["images"].size(), 2u) << preview.dump(2);
    EXPECT_NE(preview["caption"].get<std::string>().find("cam1 | cam2"), std::string::npos);
    ASSERT_TRUE(preview["rect"].is_array()) << "the preview was not drawn: " << preview.dump(2);
    const cv::Mat image = read_screenshot(png);
    ASSERT_FALSE(image.empty()) << png;
    const auto rect = preview["rect"].get<std::vector<float>>();
    const cv::Rect area(static_cast<int>(rect[0]) + 2, static_cast<int>(rect[1]) + 2,
                        static_cast<int>(rect[2]) - 4, static_cast<int>(rect[3]) - 4);
    ASSERT_GT(area.area(), 2000) << "a small but visible preview";
    ASSERT_LE(area.x + area.width, image.cols);
    ASSERT_GE(area.x, image.cols - 360) << "inside the device panel (360 px on the right)";
    // Camera images: many grey levels (the lit block, its shading, the dark floor); a panel
    // without them has its background and a few text shades.
    std::set<int> greys;
    int bright = 0;
    for (int y = area.y; y < area.y + area.height; ++y) {
        for (int x = area.x; x < area.x + area.width; ++x) {
            const cv::Vec3b p = image.at<cv::Vec3b>(y, x);
            if (p[0] == p[1] && p[1] == p[2]) greys.insert(p[0]);
            bright += p[0] > 120;
        }
    }
    EXPECT_GT(greys.size(), 40u) << "the camera images are not in the screenshot";
    EXPECT_GT(bright, area.area() / 50) << "the lit block";
}

TEST_F(FieldDevice, AnOutOfRangeSettingIsNotAppliedAndSaysWhy) {
    const fs::path session = dir_ / "session", state_file = dir_ / "state.json";
    const auto r = field("--session " + session.string() +
                         " --device sim:tof/small-block --connect "
                         "--apply-setting angular_step_deg=50 --frames 1 --dump-state " +
                         state_file.string());
    ASSERT_EQ(r.exit_code, 0) << r.output;  // the app keeps running
    const json state = read_json(state_file);
    ASSERT_TRUE(state.is_object()) << state_file;
    const json& settings = state["device_settings"];
    EXPECT_TRUE(settings["message_is_error"].get<bool>()) << settings.dump(2);
    const std::string message = settings["message"];
    EXPECT_NE(message.find("Angular step 50"), std::string::npos) << message;
    EXPECT_NE(message.find("outside 0.02-5"), std::string::npos) << message;
    const json* step = applied(state, "angular_step_deg");
    ASSERT_NE(step, nullptr);
    EXPECT_LT((*step)["value"].get<double>(), 5.0) << "unchanged";
    // A scanner without cameras: no images, and the panel says so.
    EXPECT_TRUE(state["camera_preview"]["images"].empty());
    EXPECT_NE(state["camera_preview"]["caption"].get<std::string>().find("no cameras"),
              std::string::npos);

    // A key the device does not have: named, nothing applied, exit 0.
    const auto unknown = field("--session " + session.string() +
                               " --device sim:tof/small-block --connect "
                               "--apply-setting exposure_us=100 --frames 1 --dump-state " +
                               state_file.string());
    ASSERT_EQ(unknown.exit_code, 0) << unknown.output;
    const std::string why = read_json(state_file)["device_settings"]["message"];
    EXPECT_NE(why.find("no setting \"exposure_us\""), std::string::npos) << why;
}

}  // namespace
