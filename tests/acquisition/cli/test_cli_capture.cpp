// `anascan capture` as a user runs it, on its error paths: a device that vanishes in the
// middle of a scan (and comes back), scans that register nowhere, a session folder that
// cannot be written, a disk that is full. Nothing acknowledged is lost.
#include <unistd.h>

#include <Eigen/Core>
#include <filesystem>
#include <nlohmann/json.hpp>
#include <regex>

#include "anascan/processing/io/ply.hpp"
#include "cli_runner.hpp"

namespace anascan {
namespace {

using testing_util::run_cli;

class CliCapture : public testing_util::Cli {
protected:
    /// A quick simulated terrestrial session: 2° sweeps of the small block.
    std::string capture(const std::string& session, const std::string& extra) {
        return "capture --device sim:tof --scene small-block --session " + session +
               " --angular-step-deg 2 --flip-after 0 --no-coverage " + extra;
    }

    nlohmann::json info(const std::string& session) {
        return nlohmann::json::parse(
            testing_util::run_cli_stdout("session info " + session + " --json").output, nullptr,
            false);
    }
};

TEST_F(CliCapture, DeviceUnpluggedMidScanStopsWithAClearErrorAndKeepsWhatWasSaved) {
    const std::string session = (dir_ / "s").string();
    const auto run =
        run_cli(capture(session, "--views 3 --sim-unplug-after 1 --reconnect-timeout-s 0"));
    EXPECT_EQ(run.exit_code, 1) << run.output;
    EXPECT_NE(run.output.find("saved scan 1 "), std::string::npos) << run.output;
    EXPECT_NE(run.output.find("capture stopped: sim:tof/small-block"), std::string::npos)
        << run.output;
    const auto j = info(session);
    ASSERT_TRUE(j.is_object());
    ASSERT_EQ(j["scans"].size(), 1u);
    EXPECT_TRUE(io::read_ply(dir_ / "s" / j["scans"][0]["file"].get<std::string>()).has_value());
    EXPECT_EQ(run_cli("session check " + session).exit_code, 0);
}

TEST_F(CliCapture, DeviceThatComesBackLetsTheSessionGoOn) {
    const std::string session = (dir_ / "s").string();
    const auto run =
        // --accept-poor: this test is about the device; these ToF views need not register.
        run_cli("--accept-poor " +
                capture(session, "--views 3 --sim-unplug-after 1 --reconnect-timeout-s 20"));
    EXPECT_EQ(run.exit_code, 0) << run.output;
    EXPECT_NE(run.output.find("back, capturing again"), std::string::npos) << run.output;
    const auto j = info(session);
    ASSERT_TRUE(j.is_object());
    EXPECT_EQ(j["scans"].size(), 3u);
}

// --tour footprint without --views: the simulated operator takes as many views as the
// block's outline needs; the terrestrial scanner's stations stand around it, one per part of
// the walk.
TEST_F(CliCapture, TheFootprintWalkTakesTheViewsTheOutlineNeeds) {
    const std::string session = (dir_ / "s").string();
    const auto run = run_cli(capture(session, "--tour footprint --no-register"));
    EXPECT_EQ(run.exit_code, 0) << run.output;
    EXPECT_NE(run.output.find("walks the block's footprint: 4 views"), std::string::npos)
        << run.output;
    const auto j = info(session);
    ASSERT_TRUE(j.is_object());
    ASSERT_EQ(j["scans"].size(), 4u);
    std::vector<Eigen::Vector3d> stations;
    for (const auto& scan : j["scans"]) {
        const auto T = scan["true_pose"].get<std::vector<double>>();
        ASSERT_EQ(T.size(), 16u);
        stations.emplace_back(T[3], T[7], T[11]);
    }
    for (std::size_t a = 0; a < stations.size(); ++a)
        for (std::size_t b = a + 1; b < stations.size(); ++b)
            EXPECT_GT((stations[a] - stations[b]).norm(), 1.0) << a << " " << b;
}

// The small block's one-sided tour of eight views: scan 4, placed against scan 3 alone, slid
// 75 mm along the top edge, the scans after it joined 4, and scan 3 ended 20.4 mm off with
// every pair agreeing. At the end of the capture each scan is registered against the rest of
// its group at once: scan 3 moves back to a better fit and is flagged. Whatever the machine's
// load makes of the registration, no scan of the model may be wrong without a warning.
TEST_F(CliCapture, AScanSlidAlongAnEdgeIsNotLeftInTheModelWithoutAWarning) {
    const std::string session = (dir_ / "s").string();
    const auto run = run_cli(
        "--accept-poor capture --device sim:structured-light --scene "
        "small-block --session " +
        session + " --views 8 --flip-after 8 --no-coverage");
    EXPECT_EQ(run.exit_code, 0) << run.output;
    EXPECT_NE(run.output.find("against its other"), std::string::npos) << run.output;
    const auto j = info(session);
    ASSERT_TRUE(j.is_object());
    ASSERT_EQ(j["scans"].size(), 8u);
    EXPECT_EQ(j["truth"]["off_1deg_5mm"].get<int>(), 0) << j["truth"].dump();
    for (const auto& scan : j["scans"]) {
        const std::string state = scan["state"];
        EXPECT_TRUE(state == "registered" || state == "flagged") << scan.dump();
        if (state != "flagged") continue;
        const std::string flagged = "scan " + std::to_string(scan["seq"].get<int>()) + " FLAGGED";
        EXPECT_NE(run.output.find(flagged), std::string::npos) << run.output;
    }
}

// A session in which no two scans joined is no model: exit code 3 (docs/exit-codes.md).
TEST_F(CliCapture, ScansThatRegisterNowhereAreReportedAndKept) {
    // Only the ground near the tripod is in range: no stone to register.
    const std::string session = (dir_ / "s").string();
    const auto run = run_cli(capture(session, "--views 2 --max-range-m 2.2"));
    EXPECT_EQ(run.exit_code, 3) << run.output;
    EXPECT_NE(run.output.find("poor result: no two of the 2 scans were joined"), std::string::npos)
        << run.output;
    EXPECT_NE(run.output.find("NOT registered"), std::string::npos) << run.output;
    const auto j = info(session);
    ASSERT_TRUE(j.is_object());
    ASSERT_EQ(j["scans"].size(), 2u);
    for (const auto& scan : j["scans"]) EXPECT_EQ(scan["state"], "failed") << scan.dump();
}

// The small block turned over, four structured-light views, captured once for the tests
// below: on one side two views match their look-alike turned by 180° (RMS and overlap like
// a right match).
class CliCaptureTurned : public ::testing::Test {
protected:
    static void SetUpTestSuite() {
        dir_ = std::filesystem::path(::testing::TempDir()) /
               ("cli-turned-" + std::to_string(::getpid()));
        std::filesystem::remove_all(dir_);
        run_ = run_cli(
            "--accept-poor capture --device sim:structured-light --scene small-block-turned "
            "--views 4 --session " +
            (dir_ / "s").string());
        info_ = nlohmann::json::parse(
            testing_util::run_cli_stdout("session info " + (dir_ / "s").string() + " --json")
                .output,
            nullptr, false);
    }
    static void TearDownTestSuite() { std::filesystem::remove_all(dir_); }
    static inline std::filesystem::path dir_;
    static inline testing_util::CliRun run_;
    static inline nlohmann::json info_;
};

// Every scan the model keeps is within 1° / 5 mm of the truth; one that contradicts its
// group is flagged and taken out, with its reason and an event, never left in the model as
// registered.
TEST_F(CliCaptureTurned, NoScanOfTheModelIsWrongWithoutAWarning) {
    ASSERT_EQ(run_.exit_code, 0) << run_.output;
    ASSERT_TRUE(info_.is_object());
    ASSERT_TRUE(info_["truth"].is_object()) << info_.dump(2);
    EXPECT_EQ(info_["truth"]["off_1deg_5mm"], 0) << info_["truth"].dump(2) << run_.output;
    std::size_t flagged = 0;
    for (const auto& scan : info_["scans"]) {
        if (scan["state"] != "flagged") continue;
        ++flagged;
        EXPECT_EQ(scan["group"], -1) << scan.dump();
        EXPECT_NE(scan["quality"].dump().find("contradicts its group"), std::string::npos)
            << scan.dump();
        EXPECT_NE(run_.output.find("scan " + std::to_string(scan["seq"].get<int>()) + " FLAGGED"),
                  std::string::npos)
            << run_.output;
    }
    std::printf("%zu flagged; truth %s\n", flagged, info_["truth"].dump().c_str());
}

// Each coverage line names what it is a percentage of (the surface estimated so far, from
// how many scans) and says that the estimate grows; the last live figure, the summary and
// the stored report agree on the holes.
TEST_F(CliCaptureTurned, CoverageSaysWhatItIsAPercentageOfAndTheHolesAgree) {
    const std::regex live(
        R"(coverage ([0-9.]+) % of the ([0-9.]+) m² surface estimated so far from ([0-9]+) )"
        R"(scans \(the estimate grows until every side is seen\), ([0-9]+) holes)");
    const std::regex end(
        R"(coverage at the end: ([0-9.]+) % of the ([0-9.]+) m² surface estimated from all )"
        R"(registered scans of the model, ([0-9]+) holes)");
    std::smatch last, summary;
    std::size_t live_lines = 0;
    for (auto it = std::sregex_iterator(run_.output.begin(), run_.output.end(), live);
         it != std::sregex_iterator(); ++it, ++live_lines)
        last = *it;
    ASSERT_GT(live_lines, 0u) << run_.output;
    ASSERT_TRUE(std::regex_search(run_.output, summary, end)) << run_.output;
    EXPECT_EQ(last[4].str(), summary[3].str()) << "live and final hole counts differ";
    EXPECT_EQ(last[1].str(), summary[1].str());
    ASSERT_TRUE(info_["coverage_report"].is_object());
    EXPECT_EQ(std::to_string(info_["coverage_report"]["hole_count"].get<int>()), summary[3].str());
}

TEST_F(CliCapture, UnwritableSessionFolderIsAClearError) {
    const auto file = dir_ / "not-a-folder";
    {
        std::FILE* f = std::fopen(file.c_str(), "w");
        std::fclose(f);
    }
    const auto run = run_cli(capture(file.string(), "--views 1"));
    EXPECT_EQ(run.exit_code, 1) << run.output;
    EXPECT_NE(run.output.find(file.string()), std::string::npos) << run.output;
}

TEST_F(CliCapture, FullDiskIsAClearErrorAndNothingIsHalfRecorded) {
    // RLIMIT_FSIZE (with SIGXFSZ ignored) makes writes past 256 KiB fail as on a full disk:
    // the session database stays below it, a scan at a 0.5° step (about 1.3 MB) does not.
    const std::string session = (dir_ / "s").string();
    const std::string command =
        "bash -c \"trap '' XFSZ; ulimit -f 256; exec " + std::string(ANASCAN_CLI) + " " +
        "capture --device sim:tof --scene small-block --session " + session +
        " --angular-step-deg 0.5 --flip-after 0 --no-coverage --views 2" + "\" 2>&1";
    const auto run = testing_util::run_shell(command);
    EXPECT_EQ(run.exit_code, 1) << run.output;
    const std::string& out = run.output;
    EXPECT_NE(out.find("NOT saved"), std::string::npos) << out;
    EXPECT_EQ(out.find("saved scan 1 "), std::string::npos) << out;
    const auto check = run_cli("session check " + session);
    EXPECT_EQ(check.exit_code, 0) << check.output;
}

}  // namespace
}  // namespace anascan
