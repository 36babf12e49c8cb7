// anascan-field SIGKILLed at random moments while its capture action records a session
// (under the virtual X server): after `session check --repair` every scan the app reported
// saved ("saved scan N" of --log-events) is in the session and reads, the session checks
// clean, and the app started again on the same session captures on after it.
// ANASCAN_WRITE_KILLS sets the kills (5 by default).
#include <gtest/gtest.h>

#include <chrono>
#include <filesystem>
#include <map>
#include <nlohmann/json.hpp>
#include <set>

#include "../acquisition/cli/kill_runner.hpp"
#include "anascan/processing/io/ply.hpp"
#include "field_app_run.hpp"

namespace anascan {
namespace {

namespace fs = std::filesystem;
using nlohmann::json;

/// seq -> file of every scan row of a session (`session info --json`).
std::map<std::int64_t, std::string> scan_files(const fs::path& session) {
    const auto info = test::run_command(
        std::string(ANASCAN_CLI) + " session info " + session.string() + " --json", false);
    const json j = json::parse(info.output, nullptr, false);
    std::map<std::int64_t, std::string> files;
    if (!j.is_object()) return files;
    for (const auto& scan : j["scans"]) files[scan["seq"].get<std::int64_t>()] = scan["file"];
    return files;
}

/// Every scan reported saved has a row in the session, and its file reads.
void expect_kept(const fs::path& session, const std::map<std::int64_t, std::string>& files,
                 const std::set<std::int64_t>& acknowledged) {
    for (std::int64_t seq : acknowledged) {
        ASSERT_TRUE(files.contains(seq)) << "scan " << seq << " was reported saved, then lost";
        auto ply = io::read_ply(session / files.at(seq));
        EXPECT_TRUE(ply) << "scan " << seq << ": " << ply.error().message;
    }
}

class FieldKills : public ::testing::Test {
protected:
    void SetUp() override {
        if (std::getenv("DISPLAY") == nullptr) GTEST_SKIP() << test::kNoDisplay;
        dir_ = test::fresh_test_dir("anascan_field_kills_");
    }
    void TearDown() override {
        std::error_code ec;
        if (!dir_.empty()) fs::remove_all(dir_, ec);
    }
    /// The app capturing `views` views of a fast simulated scanner into `session`.
    static std::vector<std::string> capturing(const fs::path& session, int views) {
        return {"--session",          session.string(),
                "--device",           "sim:tof/small-block",
                "--angular-step-deg", "0.5",
                "--capture-views",    std::to_string(views),
                "--tour-views",       "12",
                "--flip-after",       "0",
                "--frames",           "3",
                "--log-events"};
    }
    fs::path dir_;
};

TEST_F(FieldKills, TheAppKilledWhileCapturingLosesNoSavedScanAndCapturesOn) {
    const auto start = std::chrono::steady_clock::now();
    const auto unkilled = testing_util::run_program_and_kill(
        ANASCAN_FIELD, capturing(dir_ / "unkilled", 4), std::chrono::minutes(10), false);
    ASSERT_TRUE(unkilled.exited_before_kill) << "the unkilled run did not end in 10 minutes";
    ASSERT_EQ(unkilled.acknowledged.size(), 4u) << "--log-events printed no saved scans";
    const auto run_time = std::chrono::duration_cast<std::chrono::milliseconds>(
        std::chrono::steady_clock::now() - start);
    const fs::path session = dir_ / "session";
    std::set<std::int64_t> acknowledged;
    int while_running = 0;
    const auto moments = testing_util::kill_moments(run_time);
    for (std::size_t k = 0; k < moments.size(); ++k) {
        const auto run = testing_util::run_program_and_kill(ANASCAN_FIELD, capturing(session, 4),
                                                            moments[k], false);
        while_running += run.exited_before_kill ? 0 : 1;
        acknowledged.insert(run.acknowledged.begin(), run.acknowledged.end());
        if (!fs::exists(session / "session.sqlite")) continue;  // killed before its creation
        const auto repaired = test::run_command(std::string(ANASCAN_CLI) + " session check " +
                                                session.string() + " --repair");
        ASSERT_EQ(repaired.exit_code, 0) << "kill " << k << ":\n" << repaired.output;
    }
    EXPECT_GT(while_running, 0);
    const auto files = scan_files(session);
    expect_kept(session, files, acknowledged);
    if (HasFatalFailure()) return;
    std::printf(
        "anascan-field: %zu kills (%d while running, run %lld ms), %zu scans reported "
        "saved, 0 lost\n",
        moments.size(), while_running, static_cast<long long>(run_time.count()),
        acknowledged.size());
    // Started again, the app captures on after the scans it had (their numbers go on). It
    // first registers the session's scans again (the live state is not kept on disk): seconds
    // per scan on a loaded machine, so the limit grows with the session (the long soak's
    // 50 kills leave about 150 scans).
    const std::chrono::seconds limit =
        std::chrono::minutes(10) + std::chrono::seconds(10) * static_cast<int>(files.size());
    const auto again =
        testing_util::run_program_and_kill(ANASCAN_FIELD, capturing(session, 2), limit, false);
    ASSERT_TRUE(again.exited_before_kill) << "not done within " << limit.count() << " s";
    ASSERT_EQ(again.acknowledged.size(), 2u);
    if (!files.empty()) {
        EXPECT_GT(*again.acknowledged.begin(), files.rbegin()->first);
    }
    EXPECT_EQ(test::run_command(std::string(ANASCAN_CLI) + " session check " + session.string())
                  .exit_code,
              0);
}

}  // namespace
}  // namespace anascan
