// `anascan session register` and `anascan session export --mesh` SIGKILLed at random moments
// of their run: every acknowledged scan stays in the session and passes `session check`, no
// output is left half-written under its final name (each is absent or complete), and the
// command run again to the end gives what an unkilled run gave. ANASCAN_WRITE_KILLS sets the
// kills per command (5 here; scripts/write-kill-soak.sh asks for more).
#include <chrono>
#include <cstdlib>
#include <filesystem>
#include <map>
#include <nlohmann/json.hpp>
#include <random>

#include "anascan/processing/io/ply.hpp"
#include "cli_runner.hpp"
#include "kill_runner.hpp"

namespace anascan {
namespace {

namespace fs = std::filesystem;
using testing_util::kill_moments;
using testing_util::run_cli;
using testing_util::run_to_end;
using testing_util::temporaries_in;

/// seq -> "file state" of every scan of a session (`session info --json`).
std::map<std::int64_t, std::string> scan_table(const fs::path& session) {
    const std::string text =
        testing_util::run_cli_stdout("session info " + session.string() + " --json").output;
    const auto j = nlohmann::json::parse(text, nullptr, false);
    std::map<std::int64_t, std::string> table;
    if (!j.is_object()) return table;
    for (const auto& scan : j["scans"]) {
        table[scan["seq"].get<std::int64_t>()] =
            scan["file"].get<std::string>() + " " + scan["state"].get<std::string>();
    }
    return table;
}

/// The scan files of a table, without their states.
std::map<std::int64_t, std::string> files_of(const std::map<std::int64_t, std::string>& table) {
    std::map<std::int64_t, std::string> files;
    for (const auto& [seq, row] : table) files[seq] = row.substr(0, row.find(' '));
    return files;
}

class WriteKills : public testing_util::Cli {
protected:
    // One simulated structured-light session of four views, captured once for the suite.
    static void SetUpTestSuite() {
        source_ = fs::path(::testing::TempDir()) / ("write-kills-" + std::to_string(::getpid()));
        fs::remove_all(source_);
        const auto run = run_cli(
            "--accept-poor capture --device sim:structured-light --scene "
            "small-block --flip-after 0 --no-coverage --views 4 --session " +
            (source_ / "session").string());
        ASSERT_EQ(run.exit_code, 0) << run.output;
    }
    static void TearDownTestSuite() { fs::remove_all(source_); }

    void SetUp() override {
        Cli::SetUp();
        session_ = dir_ / "session";
        fs::copy(source_ / "session", session_, fs::copy_options::recursive);
        acknowledged_ = files_of(scan_table(session_));
        ASSERT_EQ(acknowledged_.size(), 4u);
    }

    /// After a kill: the session passes `check` and still holds every acknowledged scan.
    void expect_session_intact(int kill) {
        const auto check = run_cli("session check " + session_.string());
        ASSERT_EQ(check.exit_code, 0) << "kill " << kill << ":\n" << check.output;
        ASSERT_EQ(files_of(scan_table(session_)), acknowledged_) << "kill " << kill;
    }

    static inline fs::path source_;
    fs::path session_;
    std::map<std::int64_t, std::string> acknowledged_;
};

TEST_F(WriteKills, SessionRegisterKilledLosesNoScanAndRerunsToTheSameResult) {
    const std::string args = "--accept-poor session register " + session_.string();
    const fs::path unkilled = dir_ / "unkilled";
    fs::copy(session_, unkilled, fs::copy_options::recursive);
    const auto run_time = run_to_end("--accept-poor session register " + unkilled.string());
    const auto expected = scan_table(unkilled);
    int while_running = 0;
    const auto moments = kill_moments(run_time);
    for (std::size_t k = 0; k < moments.size(); ++k) {
        const auto run = testing_util::run_and_kill(
            {"--accept-poor", "session", "register", session_.string()}, moments[k], false);
        if (!run.exited_before_kill) ++while_running;
        expect_session_intact(static_cast<int>(k));
        if (HasFatalFailure()) return;
    }
    run_to_end(args);
    EXPECT_EQ(scan_table(session_), expected) << "the rerun decided differently";
    std::printf(
        "session register: %zu kills (%d while running, run %lld ms), 0 scans lost, "
        "%d temporaries left\n",
        moments.size(), while_running, static_cast<long long>(run_time.count()),
        temporaries_in(session_));
    EXPECT_GT(while_running, 0);
}

/// Each output is absent or complete: a PLY that parses to the unkilled run's size.
void expect_absent_or_complete(const fs::path& file, std::size_t points, std::size_t triangles,
                               int kill) {
    if (!fs::exists(file)) return;
    auto ply = io::read_ply(file);
    ASSERT_TRUE(ply) << "kill " << kill << ": half-written " << ply.error().message;
    EXPECT_EQ(ply->cloud.size(), points) << file << ", kill " << kill;
    EXPECT_EQ(ply->triangles.size(), triangles) << file << ", kill " << kill;
}

TEST_F(WriteKills, SessionExportWithAMeshKilledLeavesNoHalfWrittenOutput) {
    const fs::path model = dir_ / "model.ply";
    const fs::path mesh = dir_ / "mesh.ply";
    const std::vector<std::string> args{
        "--accept-poor", "session", "export", session_.string(), "--out",           model.string(),
        "--voxel-mm",    "3",       "--mesh", mesh.string(),     "--resolution-mm", "6"};
    std::string line;
    for (const std::string& a : args) line += a + " ";
    const auto run_time = run_to_end(line);
    auto ref_model = io::read_ply(model);
    auto ref_mesh = io::read_ply(mesh);
    ASSERT_TRUE(ref_model && ref_mesh);
    ASSERT_GT(ref_mesh->triangles.size(), 0u);
    int while_running = 0;
    const auto moments = kill_moments(run_time);
    for (std::size_t k = 0; k < moments.size(); ++k) {
        fs::remove(model);
        fs::remove(mesh);
        if (!testing_util::run_and_kill(args, moments[k], false).exited_before_kill)
            ++while_running;
        const int kill = static_cast<int>(k);
        expect_absent_or_complete(model, ref_model->cloud.size(), 0, kill);
        expect_absent_or_complete(mesh, ref_mesh->cloud.size(), ref_mesh->triangles.size(), kill);
        expect_session_intact(kill);
        if (HasFatalFailure()) return;
    }
    run_to_end(line);
    expect_absent_or_complete(model, ref_model->cloud.size(), 0, -1);
    expect_absent_or_complete(mesh, ref_mesh->cloud.size(), ref_mesh->triangles.size(), -1);
    EXPECT_TRUE(fs::exists(model) && fs::exists(mesh));
    std::printf(
        "session export --mesh: %zu kills (%d while running, run %lld ms), 0 "
        "half-written outputs, %d temporaries left\n",
        moments.size(), while_running, static_cast<long long>(run_time.count()),
        temporaries_in(dir_));
    EXPECT_GT(while_running, 0);
}

}  // namespace
}  // namespace anascan
