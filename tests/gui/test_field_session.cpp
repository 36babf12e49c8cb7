// anascan-field attached to capture sessions, under a virtual X server (xvfb-run, Mesa
// llvmpipe): a session made by `anascan capture` is shown as `anascan session info` and
// `anascan coverage` report it; captures driven from the app's capture action register;
// an unplugged simulated scanner and an unwritable folder give a message, not a crash.
#include <gtest/gtest.h>
#include <unistd.h>

#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <map>
#include <nlohmann/json.hpp>
#include <opencv2/core/mat.hpp>
#include <string>

#include "field_app_run.hpp"
#include "screenshot_png.hpp"

using anascan::field::test::read_screenshot;

namespace fs = std::filesystem;
using nlohmann::json;

namespace {

using anascan::test::fraction_not;
using anascan::test::kClearRgb;
using anascan::test::RunResult;

RunResult run(const std::string& program, const std::string& args, bool stderr_too = true) {
    return anascan::test::run_command(program + " " + args, stderr_too);
}

json read_json(const fs::path& file) {
    std::ifstream in(file);
    return json::parse(in, nullptr, false);
}

/// A scan of kDevice is a PLY file of about 1.3 MB; the session database and a screenshot
/// fit in this file size limit, a scan does not.
constexpr int kFullDiskLimitKiB = 800;

/// A fast simulated device: the terrestrial (time-of-flight) scanner at a coarse step.
const std::string kDevice = "--device sim:tof/small-block --angular-step-deg 0.5";

int registered_rows(const json& state) {
    int n = 0;
    for (const auto& row : state["scans"]) n += row["state"] == "registered";
    return n;
}

class FieldSession : public ::testing::Test {
protected:
    void SetUp() override {
        if (std::getenv("DISPLAY") == nullptr) GTEST_SKIP() << anascan::test::kNoDisplay;
        dir_ = anascan::test::fresh_test_dir("anascan_field_session_");
    }
    void TearDown() override {
        std::error_code ec;
        if (!dir_.empty()) fs::remove_all(dir_, ec);
    }
    RunResult field(const std::string& args) const { return run(ANASCAN_FIELD, args); }
    RunResult cli(const std::string& args) const { return run(ANASCAN_CLI, args); }
    /// A command's JSON document (stdout); null when it failed.
    json cli_json(const std::string& args) const {
        const RunResult r = run(ANASCAN_CLI, args, false);
        EXPECT_EQ(r.exit_code, 0) << args << ": " << r.output;
        return json::parse(r.output, nullptr, false);
    }
    // The app's rows and coverage are what `session info` and `coverage` report.
    void expect_state_as_session_info(const fs::path& session, const fs::path& state_file) {
        const json state = read_json(state_file);
        ASSERT_TRUE(state.is_object()) << state_file;
        const json expected = cli_json("session info " + session.string() + " --json");
        ASSERT_TRUE(expected.is_object());
        ASSERT_EQ(state["scans"].size(), expected["scans"].size());
        for (std::size_t i = 0; i < state["scans"].size(); ++i) {
            EXPECT_EQ(state["scans"][i]["seq"], expected["scans"][i]["seq"]);
            EXPECT_EQ(state["scans"][i]["state"], expected["scans"][i]["state"]);
            EXPECT_EQ(state["scans"][i]["group"], expected["scans"][i]["group"]);
        }
        ASSERT_GT(registered_rows(state), 0);
        EXPECT_GT(state["points_total"].get<double>(), 0.0);

        const json cov = cli_json("coverage " + session.string() + " --json");
        ASSERT_TRUE(cov.is_object());
        ASSERT_TRUE(state["coverage_fraction"].is_number()) << state.dump();
        EXPECT_GT(cov["fraction"].get<double>(), 0.0) << "a session with coverage";
        EXPECT_NEAR(state["coverage_fraction"].get<double>(), cov["fraction"].get<double>(), 1e-4);
    }

    void expect_model_drawn(const fs::path& png) {
        const cv::Mat image = read_screenshot(png);
        ASSERT_FALSE(image.empty()) << png;
        // The view lies between the scan list (450 px) and the device panel (360 px); a banner
        // (this 2-view session may be split) covers up to about 260 px of its top.
        EXPECT_GT(fraction_not(image, cv::Rect(500, 300, 370, 300), kClearRgb), 0.05)
            << "no model drawn in the view";
    }

    void expect_reregistered_from_the_list(const fs::path& session, const fs::path& state_file) {
        // Re-register scan 2 from the scan list's action (the session is opened for capture):
        // the row gets a new decision and the session records the operator's action.
        const int events_before =
            cli_json("session info " + session.string() + " --json")["events"];
        const RunResult again =
            field("--session " + session.string() +
                  " --reregister-scan 2 --frames 2 --dump-state " + state_file.string());
        ASSERT_EQ(again.exit_code, 0) << again.output;
        const json after = read_json(state_file);
        ASSERT_EQ(after["scans"].size(), 2u) << after.dump(2);
        EXPECT_NE(after["scans"][1]["state"], "queued") << after.dump(2);
        EXPECT_EQ(after["queued_registrations"], 0);
        EXPECT_EQ(after["last_error"], "") << after.dump(2);
        const json info = cli_json("session info " + session.string() + " --json");
        EXPECT_GT(info["events"].get<int>(), events_before) << "the re-register event";
    }

    void expect_damage_reported(const fs::path& session, const fs::path& state_file) {
        // After a "crash" that damaged a scan file, reopening shows what `session check` found.
        fs::resize_file(session / "scans" / "scan_000002.ply", 200);
        const RunResult reopened = field("--session " + session.string() +
                                         " --frames 1 --dump-state " + state_file.string());
        ASSERT_EQ(reopened.exit_code, 0) << reopened.output;
        const std::string check = read_json(state_file)["session_check"];
        EXPECT_NE(check.find("scan_000002.ply"), std::string::npos) << check;
        EXPECT_NE(check.find("--repair"), std::string::npos) << check;
    }

    fs::path dir_;
};

TEST_F(FieldSession, ShowsASessionAsSessionInfoAndCoverageReportIt) {
    const fs::path session = dir_ / "session";
    // Two structured-light views of the small block (about 7 s): a coverage figure, holes.
    const RunResult captured =
        cli("--accept-poor capture --device sim:structured-light --scene small-block --session " +
            session.string() + " --views 2 --flip-after 0");
    ASSERT_EQ(captured.exit_code, 0) << captured.output;
    const fs::path png = dir_ / "out.png", state_file = dir_ / "state.json";
    const RunResult r = field("--session " + session.string() + " --screenshot " + png.string() +
                              " --frames 5 --dump-state " + state_file.string());
    ASSERT_EQ(r.exit_code, 0) << r.output;
    expect_state_as_session_info(session, state_file);
    expect_model_drawn(png);
    expect_reregistered_from_the_list(session, state_file);
    expect_damage_reported(session, state_file);
}

/// Share of the pixels in `rect` whose colour is the mesh's interpolated orange, shaded by
/// the headlight (any brightness: red well above green, green well above blue).
double orange_share(const cv::Mat& bgr, cv::Rect rect) {
    int n = 0;
    for (int y = rect.y; y < rect.y + rect.height; ++y) {
        for (int x = rect.x; x < rect.x + rect.width; ++x) {
            const cv::Vec3b p = bgr.at<cv::Vec3b>(y, x);
            n += p[2] > 60 && p[2] > 1.5 * p[1] && p[1] > 1.8 * p[0];
        }
    }
    return double(n) / rect.area();
}

TEST_F(FieldSession, TheMeshOfTheSessionIsMadeOnRequestAndShownWithItsInterpolatedPart) {
    const fs::path session = dir_ / "session";
    // Two structured-light views of one side: much of the stone was never seen.
    const RunResult captured =
        cli("--accept-poor capture --device sim:structured-light --scene small-block --session " +
            session.string() + " --views 2 --flip-after 0 --no-coverage");
    ASSERT_EQ(captured.exit_code, 0) << captured.output;
    const fs::path png = dir_ / "mesh.png", state_file = dir_ / "state.json";
    const RunResult r = field("--session " + session.string() +
                              " --make-mesh --mesh-resolution-mm 4 --screenshot " + png.string() +
                              " --dump-state " + state_file.string());
    ASSERT_EQ(r.exit_code, 0) << r.output;
    const json mesh = read_json(state_file)["mesh"];
    ASSERT_EQ(mesh["status"], "ready") << mesh.dump(2);
    EXPECT_TRUE(mesh["shown"].get<bool>());
    EXPECT_GT(mesh["triangles"].get<int>(), 1000);
    EXPECT_EQ(mesh["triangles_on_gpu"], mesh["triangles"]);
    // Of the model group (the views may not have joined: then one scan).
    EXPECT_GE(mesh["scans"].get<int>(), 1);
    EXPECT_LE(mesh["scans"].get<int>(), registered_rows(read_json(state_file)));
    EXPECT_GT(mesh["interpolated_share"].get<double>(), 0.05) << "one side was never seen";
    EXPECT_LT(mesh["interpolated_share"].get<double>(), 0.95);
    EXPECT_EQ(mesh["outdated"], "");
    EXPECT_NE(mesh["summary"].get<std::string>().find("interpolated"), std::string::npos);
    const cv::Mat image = read_screenshot(png);
    ASSERT_FALSE(image.empty());
    // The view lies between the scan list (300 px x font scale 1.5) and the device panel.
    const cv::Rect view(460, 60, image.cols - 460 - 370, image.rows - 200);
    EXPECT_GT(orange_share(image, view), 0.01) << "no interpolated (orange) surface drawn";
    EXPECT_GT(fraction_not(image, view, kClearRgb), 0.05) << "no mesh drawn in the view";
}

TEST_F(FieldSession, AMeshAskedForBeforeAnyScanSaysWhy) {
    const fs::path state_file = dir_ / "state.json";
    const RunResult r = field("--session " + (dir_ / "new").string() +
                              " --make-mesh --frames 2 --dump-state " + state_file.string());
    ASSERT_EQ(r.exit_code, 0) << r.output;
    const json state = read_json(state_file);
    EXPECT_EQ(state["mesh"]["status"], "failed") << state.dump(2);
    EXPECT_NE(state["mesh"]["message"].get<std::string>().find("capture first"), std::string::npos);
    EXPECT_FALSE(state["mesh"]["shown"].get<bool>());
}

TEST_F(FieldSession, CapturesFromTheCaptureActionRegisterLive) {
    const fs::path session = dir_ / "live", state_file = dir_ / "state.json";
    const RunResult r = field("--session " + session.string() + " " + kDevice +
                              " --capture-views 3 --tour-views 12 --flip-after 0 --frames 5 "
                              "--dump-state " +
                              state_file.string());
    ASSERT_EQ(r.exit_code, 0) << r.output;
    EXPECT_NE(r.output.find("frames while capturing or registering"), std::string::npos)
        << r.output;
    const json state = read_json(state_file);
    ASSERT_TRUE(state.is_object()) << state_file;
    EXPECT_EQ(state["scans"].size(), 3u) << state.dump(2);
    EXPECT_GE(registered_rows(state), 2) << state.dump(2);
    EXPECT_EQ(state["queued_registrations"], 0);
    EXPECT_GT(state["points_total"].get<double>(), 0.0);
    // The device panel shows the last scan as the scanner saw it.
    EXPECT_TRUE(state["preview"]["shown"].get<bool>()) << state["preview"].dump();
    EXPECT_GT(state["preview"]["height_px"].get<int>(), 0);
    EXPECT_NE(state["preview"]["caption"].get<std::string>().find("Scan 3"), std::string::npos);
    // The session on disk holds what the app showed.
    const json stored = cli_json("session info " + session.string() + " --json");
    ASSERT_TRUE(stored.is_object());
    EXPECT_EQ(stored["scans"].size(), 3u);
}

TEST_F(FieldSession, CaptureUsesTheSessionsOwnDeviceAndLoneScansAreUnjoined) {
    const fs::path session = dir_ / "tof";
    const RunResult captured = cli("--accept-poor capture " + kDevice + " --session " +
                                   session.string() + " --views 3 --flip-after 0");
    ASSERT_EQ(captured.exit_code, 0) << captured.output;
    const json stored = cli_json("session info " + session.string() + " --json");
    ASSERT_TRUE(stored.is_object());
    ASSERT_FALSE(stored["scans"].empty());
    const std::string device = stored["scans"].back()["device_id"];
    const fs::path state_file = dir_ / "state.json";
    const RunResult r =
        field("--session " + session.string() + " --frames 1 --dump-state " + state_file.string());
    ASSERT_EQ(r.exit_code, 0) << r.output;
    const json state = read_json(state_file);
    ASSERT_TRUE(state.is_object()) << state_file;
    const int active = state["active_device"];
    ASSERT_GE(active, 0);
    EXPECT_EQ(state["devices"][active]["id"], device) << "Capture would add another stone";
    // A registered scan alone in its group joined nothing: "unjoined", no RMS; the others
    // "ok".
    std::map<int, int> members;
    for (const auto& row : state["scans"])
        if (row["state"] == "registered") ++members[row["group"].get<int>()];
    for (const auto& row : state["scans"]) {
        if (row["state"] != "registered") continue;
        const bool alone = members[row["group"].get<int>()] == 1;
        EXPECT_EQ(row["list_state"], alone ? "unjoined" : "ok") << row.dump();
        if (alone) {
            EXPECT_TRUE(row["rms_mm"].is_null()) << row.dump();
        }
    }
}

TEST_F(FieldSession, AnUnpluggedScannerIsReportedAndTheAppGoesOn) {
    const fs::path session = dir_ / "unplug", state_file = dir_ / "state.json";
    const RunResult r = field("--session " + session.string() + " " + kDevice +
                              " --sim-unplug-after 1 --capture-views 3 --tour-views 12 "
                              "--flip-after 0 --frames 3 --dump-state " +
                              state_file.string());
    ASSERT_EQ(r.exit_code, 0) << r.output;
    const json state = read_json(state_file);
    ASSERT_TRUE(state.is_object()) << state_file;
    const std::string error = state["last_error"];
    EXPECT_NE(error.find("unplugged"), std::string::npos) << error;
    EXPECT_NE(error.find("sim:tof"), std::string::npos) << "the message names the device";
    // The capture after the unplug reopened the device: two scans, nothing lost.
    EXPECT_EQ(state["scans"].size(), 2u) << state.dump(2);
}

TEST_F(FieldSession, AFullDiskIsReportedInTheBannerAndTheAppGoesOn) {
    // RLIMIT_FSIZE (SIGXFSZ ignored) makes writes past the limit fail as on a full disk:
    // room for the session database and the screenshot, not for a scan file.
    const fs::path session = dir_ / "full", png = dir_ / "full.png",
                   state_file = dir_ / "state.json";
    const std::string command = "bash -c \"trap '' XFSZ; ulimit -f " +
                                std::to_string(kFullDiskLimitKiB) + "; exec " + ANASCAN_FIELD +
                                " --session " + session.string() + " " + kDevice +
                                " --capture-views 2 --tour-views 12 --flip-after 0 --frames 3 "
                                "--screenshot " +
                                png.string() + " --dump-state " + state_file.string() + "\"";
    const RunResult r = anascan::test::run_command(command);
    ASSERT_EQ(r.exit_code, 0) << r.output;  // the app went on to draw its frames and exit
    const json state = read_json(state_file);
    ASSERT_TRUE(state.is_object()) << state_file;
    const std::string error = state["last_error"];
    EXPECT_NE(error.find("DISK FULL"), std::string::npos) << error;
    EXPECT_NE(error.find("NOT saved"), std::string::npos) << error;
    EXPECT_EQ(state["banner_kind"], "capture-failed") << state.dump(2);
    EXPECT_TRUE(state["scans"].empty()) << "nothing half-recorded: " << state.dump(2);
    // The red banner over the top of the view (the view starts at 450 px).
    const cv::Mat image = read_screenshot(png);
    ASSERT_FALSE(image.empty()) << png;
    const cv::Vec3b banner_red{191, 13, 13};  // ImVec4(0.75, 0.05, 0.05)
    EXPECT_LT(fraction_not(image, cv::Rect(460, 5, 300, 60), banner_red), 0.5)
        << "no red banner over the view";
    const RunResult check = cli("session check " + session.string());
    EXPECT_EQ(check.exit_code, 0) << check.output;
}

TEST_F(FieldSession, AnUnwritableFolderIsReportedAndTheAppGoesOn) {
    // Even root cannot create a folder in /proc.
    const std::string session = "/proc/anascan_field_no_such_session";
    const fs::path state_file = dir_ / "state.json";
    const RunResult r = field("--session " + session + " " + kDevice +
                              " --capture-views 1 --frames 2 --dump-state " + state_file.string());
    ASSERT_EQ(r.exit_code, 0) << r.output;
    const json state = read_json(state_file);
    ASSERT_TRUE(state.is_object()) << state_file;
    const std::string error = state["last_error"];
    EXPECT_NE(error.find("cannot open session"), std::string::npos) << error;
    EXPECT_NE(error.find(session), std::string::npos) << error;
    EXPECT_TRUE(state["scans"].empty());
}

}  // namespace

namespace {

// The small block turned over, four structured-light views: one view matches its look-alike
// turned by 180° (RMS and overlap like a right match). The app must not show it "ok": it
// is listed as contradicting the model, left out of the view, and the banner says so.
TEST_F(FieldSession, AScanThatContradictsItsGroupIsFlaggedAndTheBannerSaysSo) {
    const fs::path session = dir_ / "turned", png = dir_ / "turned.png",
                   state_file = dir_ / "state.json";
    const RunResult captured =
        cli("--accept-poor capture --device sim:structured-light --scene small-block-turned "
            "--views 4 --no-coverage --session " +
            session.string());
    ASSERT_EQ(captured.exit_code, 0) << captured.output;
    const RunResult r = field("--session " + session.string() + " --frames 3 --screenshot " +
                              png.string() + " --dump-state " + state_file.string());
    ASSERT_EQ(r.exit_code, 0) << r.output;
    const json state = read_json(state_file);
    ASSERT_TRUE(state.is_object()) << state_file;
    int flagged = 0;
    for (const auto& row : state["scans"]) {
        if (row["state"] != "flagged") continue;
        ++flagged;
        EXPECT_EQ(row["list_state"], "CONTRADICTS") << row.dump();
    }
    ASSERT_GE(flagged, 1) << state.dump(2) << captured.output;
    EXPECT_EQ(state["banner_kind"], "disagree") << state.dump(2);
    EXPECT_NE(state["banner"].get<std::string>().find("contradict"), std::string::npos);
    const cv::Mat image = read_screenshot(png);
    ASSERT_FALSE(image.empty()) << png;
    const cv::Vec3b banner_red{191, 13, 13};  // ImVec4(0.75, 0.05, 0.05), as the failure's
    EXPECT_LT(fraction_not(image, cv::Rect(460, 5, 300, 60), banner_red), 0.5)
        << "no red banner over the view";
}

}  // namespace
