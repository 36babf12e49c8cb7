// `anascan capture` as a user runs it, on its error paths: a device that vanishes in the
// middle of a scan (and comes back), scans that register nowhere, a session folder that
// cannot be written, a disk that is full. Nothing acknowledged is lost.
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
