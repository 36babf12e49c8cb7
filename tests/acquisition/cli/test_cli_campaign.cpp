// `anascan campaign ...` as a user runs it: bad input gets clear messages (unreadable,
// empty, duplicate and background-only scans, a newer schema, a locked store), a rerun
// resumes without redoing finished work, and a small simulated campaign finds its stones.
#include <gtest/gtest.h>
#include <sqlite3.h>

#include <filesystem>
#include <fstream>

#include "cli_runner.hpp"

namespace anascan {
namespace {

namespace fs = std::filesystem;
using testing_util::run_cli;
using testing_util::run_shell;

/// The "run now" count of a stage in `campaign register`'s report ("" when not found).
std::string run_now(const std::string& output, const std::string& stage) {
    const std::string head = "stage " + stage + ": ";
    const std::size_t at = output.find(head);
    if (at == std::string::npos) return "";
    const std::size_t comma = output.find(", ", at);
    const std::size_t end = output.find(" run now", comma);
    if (comma == std::string::npos || end == std::string::npos) return "";
    return output.substr(comma + 2, end - comma - 2);
}

class CampaignCli : public testing_util::Cli {
protected:
    /// A small simulated campaign (coarse scans of procedural stones) in DIR/scans.
    void simulate(const std::string& extra = "--stones 1 --scans-per-stone 1") {
        const auto run = run_cli("sim campaign --spacing-mm 10 --seed 3 --out " +
                                 (dir_ / "scans").string() + " " + extra);
        ASSERT_EQ(run.exit_code, 0) << run.output;
    }
    void sql(const std::string& statement) {
        sqlite3* db = nullptr;
        ASSERT_EQ(sqlite3_open((dir_ / "c" / "campaign.sqlite").c_str(), &db), SQLITE_OK);
        EXPECT_EQ(sqlite3_exec(db, statement.c_str(), nullptr, nullptr, nullptr), SQLITE_OK);
        sqlite3_close(db);
    }
    std::string campaign() const { return (dir_ / "c").string(); }
};

TEST_F(CampaignCli, MissingScanIsNamedAndRepeatsAreRecordedOnce) {
    simulate();
    const std::string scan = (dir_ / "scans" / "scan_0000.ply").string();
    auto run =
        run_cli("campaign init " + campaign() + " " + scan + " " + (dir_ / "nope.ply").string());
    EXPECT_EQ(run.exit_code, 1);
    EXPECT_NE(run.output.find("nope.ply: no such scan file"), std::string::npos) << run.output;
    run = run_cli("campaign init " + campaign() + " " + scan + " " + scan);
    EXPECT_EQ(run.exit_code, 0) << run.output;
    EXPECT_NE(run.output.find("listed more than once"), std::string::npos) << run.output;
    EXPECT_NE(run.output.find("1 scans"), std::string::npos) << run.output;
    run = run_cli("campaign init " + campaign() + " " + scan);
    EXPECT_EQ(run.exit_code, 1);
    EXPECT_NE(run.output.find("already a campaign folder"), std::string::npos) << run.output;
}

TEST_F(CampaignCli, BadScansAreReportedAndTheRestIsRegisteredOnce) {
    simulate("--stones 2 --scans-per-stone 3 --background-scans 1");
    const fs::path scans = dir_ / "scans";
    std::ofstream(scans / "broken.ply")
        << "ply\nformat ascii 1.0\nelement vertex 5\nend_header\n1 2\n";
    fs::copy_file(scans / "scan_0001.ply", scans / "copy.ply");
    std::ofstream(scans / "list.txt", std::ios::app) << "broken.ply\ncopy.ply\n";
    auto run = run_cli("campaign init " + campaign() + " --list " + (scans / "list.txt").string() +
                       " --candidates-per-scan 3");
    ASSERT_EQ(run.exit_code, 0) << run.output;
    run = run_cli("campaign register " + campaign());
    ASSERT_EQ(run.exit_code, 0) << run.output;
    EXPECT_NE(run.output.find("broken.ply: unreadable scan"), std::string::npos) << run.output;
    EXPECT_NE(run.output.find("copy.ply: the same points as"), std::string::npos) << run.output;
    EXPECT_NE(run.output.find("featureless"), std::string::npos) << run.output;  // The ground.
    EXPECT_NE(run.output.find("scans placed"), std::string::npos) << run.output;
    // A rerun finds everything done; with two pair results removed it redoes those two only.
    run = run_cli("campaign register " + campaign());
    ASSERT_EQ(run.exit_code, 0) << run.output;
    EXPECT_EQ(run_now(run.output, "prepare"), "0") << run.output;
    EXPECT_EQ(run_now(run.output, "pairs"), "0") << run.output;
    EXPECT_EQ(run_now(run.output, "multiview"), "0") << run.output;
    sql("UPDATE pairs SET result_json = '' WHERE rowid IN (SELECT rowid FROM pairs LIMIT 2)");
    run = run_cli("campaign register " + campaign());
    ASSERT_EQ(run.exit_code, 0) << run.output;
    EXPECT_EQ(run_now(run.output, "pairs"), "2") << run.output;
    // A pair's stored result damaged by another tool: named, found, repaired, redone.
    sql(R"(UPDATE pairs SET result_json = '{"verified":"yes"}' WHERE rowid = 1)");
    for (const std::string command : {"campaign status ", "campaign register "}) {
        run = run_cli(command + campaign());
        EXPECT_EQ(run.exit_code, 1) << run.output;
        EXPECT_NE(run.output.find("the pair's result is damaged"), std::string::npos) << run.output;
    }
    run = run_cli("campaign check " + campaign());
    EXPECT_EQ(run.exit_code, 1) << run.output;
    EXPECT_NE(run.output.find("pair-result: pair"), std::string::npos) << run.output;
    run = run_cli("campaign check --repair " + campaign());
    EXPECT_EQ(run.exit_code, 0) << run.output;
    run = run_cli("campaign register " + campaign());
    ASSERT_EQ(run.exit_code, 0) << run.output;
    EXPECT_EQ(run_now(run.output, "pairs"), "1") << run.output;
    EXPECT_EQ(run_cli("campaign status " + campaign()).exit_code, 0);
}

TEST_F(CampaignCli, NewerSchemaAndLockedStoreAreRefusedClearly) {
    simulate();
    auto run =
        run_cli("campaign init " + campaign() + " " + (dir_ / "scans" / "scan_0000.ply").string());
    ASSERT_EQ(run.exit_code, 0) << run.output;
    run = run_shell("flock " + campaign() + "/campaign.lock " + ANASCAN_CLI +
                    " campaign register " + campaign() + " 2>&1");
    EXPECT_EQ(run.exit_code, 1);
    EXPECT_NE(run.output.find("in use by another job"), std::string::npos) << run.output;
    sql("PRAGMA user_version = 99");
    run = run_cli("campaign register " + campaign());
    EXPECT_EQ(run.exit_code, 1);
    EXPECT_NE(run.output.find("newer anascan (schema 99"), std::string::npos) << run.output;
    run = run_cli("campaign status " + campaign());
    EXPECT_EQ(run.exit_code, 1);
    EXPECT_NE(run.output.find("newer anascan"), std::string::npos) << run.output;
}

#ifdef ANASCAN_MPIRUN
// Two MPI ranks (rank 0 owns the store and works too) give the same stones and poses as one
// process.
TEST_F(CampaignCli, TwoMpiRanksGiveTheSameResultAsOneProcess) {
    simulate("--stones 2 --scans-per-stone 3");
    const std::string list = (dir_ / "scans" / "list.txt").string();
    for (const char* name : {"one", "two"}) {
        const auto run = run_cli("campaign init " + (dir_ / name).string() + " --list " + list +
                                 " --candidates-per-scan 3");
        ASSERT_EQ(run.exit_code, 0) << run.output;
    }
    auto run = run_cli("campaign register " + (dir_ / "one").string());
    ASSERT_EQ(run.exit_code, 0) << run.output;
    run = run_shell(std::string("OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1 ") +
                    ANASCAN_MPIRUN + " -np 2 --oversubscribe " + ANASCAN_CLI +
                    " campaign register " + (dir_ / "two").string() + " 2>&1");
    ASSERT_EQ(run.exit_code, 0) << run.output;
    EXPECT_NE(run.output.find("ranks: 2"), std::string::npos) << run.output;
    const std::string query =
        "SELECT source, target, json_extract(result_json, '$.verified'), "
        "json_extract(result_json, '$.T_target_source') FROM pairs ORDER BY 1, 2";
    const auto dump = [&](const char* name) {
        return run_shell("sqlite3 " + (dir_ / name / "campaign.sqlite").string() + " \"" + query +
                         "; SELECT scans_json, json_extract(result_json, '$.scans') FROM stones\"")
            .output;
    };
    const std::string one = dump("one");
    EXPECT_GT(one.size(), 10u);
    EXPECT_EQ(one, dump("two"));
}
#endif

}  // namespace
}  // namespace anascan
