// `anascan session info|check|export|exclude|note|turned-over` on a session written through
// the store, as a user runs them.
#include <gtest/gtest.h>

#include <nlohmann/json.hpp>

#include "anascan/acquisition/store/session_store.hpp"
#include "anascan/processing/io/ply.hpp"
#include "anascan/processing/io/stanford_conf.hpp"
#include "cli_runner.hpp"
#include "session_test_support.hpp"

namespace anascan {
namespace {

namespace fs = std::filesystem;
using acquisition::RegistrationUpdate;
using acquisition::ScanState;
using acquisition::SessionOpenMode;
using acquisition::SessionStore;
using testing_util::Cli;
using testing_util::make_scan;
using testing_util::make_test_pose;
using testing_util::run_cli;

bool contains(const std::string& text, const std::string& part) {
    return text.find(part) != std::string::npos;
}

class SessionCli : public Cli {
protected:
    // Four scans: 1-3 registered in group 0 (3 with a true pose), 4 failed.
    void SetUp() override {
        Cli::SetUp();
        session_ = dir_ / "stone-1";
        auto store = SessionStore::open(session_, SessionOpenMode::kCreateOrOpen);
        ASSERT_TRUE(store) << store.error().message;
        for (int i = 1; i <= 4; ++i) {
            auto saved = (*store)->save_scan(
                make_scan(100u * i, i), i == 3 ? std::optional(make_test_pose(3)) : std::nullopt);
            ASSERT_TRUE(saved) << saved.error().message;
            RegistrationUpdate u{ScanState::kRegistered, 0, make_test_pose(i), "{}", 0.01 * i};
            if (i == 4) u = {ScanState::kFailed, -1, std::nullopt, "{}", std::nullopt};
            ASSERT_TRUE((*store)->record_registration(i, u));
        }
        ASSERT_TRUE((*store)->set_value("coverage", R"({"fraction":0.625,"holes":[]})"));
    }
    std::string quoted() const { return "'" + session_.string() + "'"; }
    nlohmann::json info() {
        const auto run = run_cli("-q session info " + quoted() + " --json");
        EXPECT_EQ(run.exit_code, 0) << run.output;
        return nlohmann::json::parse(run.output);
    }
    fs::path session_;
};

TEST_F(SessionCli, InfoJsonListsScansPosesAndCoverage) {
    const nlohmann::json doc = info();
    ASSERT_EQ(doc["scans"].size(), 4u);
    const auto& s3 = doc["scans"][2];
    EXPECT_EQ(s3["seq"], 3);
    EXPECT_EQ(s3["file"], "scans/scan_000003.ply");
    EXPECT_EQ(s3["state"], "registered");
    EXPECT_EQ(s3["group"], 0);
    ASSERT_EQ(s3["pose"].size(), 16u);
    EXPECT_DOUBLE_EQ(s3["pose"][3].get<double>(), make_test_pose(3).translation().x());
    EXPECT_EQ(s3["true_pose"].size(), 16u);
    EXPECT_DOUBLE_EQ(s3["latency_s"].get<double>(), 0.03);
    EXPECT_TRUE(doc["scans"][0]["true_pose"].is_null());
    EXPECT_EQ(doc["scans"][3]["state"], "failed");
    EXPECT_TRUE(doc["scans"][3]["pose"].is_null());
    EXPECT_TRUE(doc["scans"][3]["latency_s"].is_null());
    EXPECT_DOUBLE_EQ(doc["coverage"].get<double>(), 0.625);
    EXPECT_EQ(doc["devices"].size(), 1u);
}

TEST_F(SessionCli, InfoPrintsATableWithUnits) {
    const auto run = run_cli("session info " + quoted());
    ASSERT_EQ(run.exit_code, 0) << run.output;
    EXPECT_TRUE(contains(run.output, "4 scans (3 registered, 1 failed, 0 queued, 0 excluded)"))
        << run.output;
    EXPECT_TRUE(contains(run.output, "coverage 62.5 %"));
    EXPECT_TRUE(contains(run.output, "latency s"));
    EXPECT_TRUE(contains(run.output, "scans/scan_000004.ply"));
}

TEST_F(SessionCli, ExcludeUndoNoteAndTurnOverAreRecorded) {
    EXPECT_EQ(run_cli("session exclude " + quoted() + " 2").exit_code, 0);
    EXPECT_EQ(info()["scans"][1]["state"], "excluded");
    EXPECT_EQ(run_cli("session exclude " + quoted() + " 2 --undo").exit_code, 0);
    EXPECT_EQ(info()["scans"][1]["state"], "registered");
    EXPECT_EQ(run_cli("session note " + quoted() + " --scan 2 'dust on the lens'").exit_code, 0);
    EXPECT_EQ(run_cli("session turned-over " + quoted() + " --after 2").exit_code, 0);
    const nlohmann::json doc = info();
    EXPECT_EQ(doc["notes"][0]["text"], "dust on the lens");
    EXPECT_EQ(doc["notes"][0]["seq"], 2);
    EXPECT_TRUE(doc["scans"][2]["turned_over_before"].get<bool>());
    const auto bad = run_cli("session exclude " + quoted() + " 99");
    EXPECT_EQ(bad.exit_code, 1);
    EXPECT_TRUE(contains(bad.output, "no scan 99")) << bad.output;
}

TEST_F(SessionCli, RegisterDecidesEveryScanAgainAndReregistersTheOnesAskedFor) {
    const auto run = run_cli("session register " + quoted() + " --scan 2");
    ASSERT_EQ(run.exit_code, 0) << run.output;
    // Scan 2 is decided twice: with the session, then on its own.
    const auto count = [&](const std::string& part) {
        std::size_t n = 0;
        for (std::size_t at = 0; (at = run.output.find(part, at)) != std::string::npos; ++at) ++n;
        return n;
    };
    const std::size_t decided_2 = count("registered scan 2:") + count("scan 2 NOT registered");
    EXPECT_EQ(decided_2, 2u) << run.output;
    const nlohmann::json doc = info();
    for (const auto& scan : doc["scans"]) EXPECT_NE(scan["state"], "queued") << scan.dump();
    auto store = SessionStore::open(session_, SessionOpenMode::kReadOnly);
    ASSERT_TRUE(store) << store.error().message;
    auto events = (*store)->events();
    ASSERT_TRUE(events);
    EXPECT_TRUE(std::any_of(events->begin(), events->end(), [](const acquisition::EventRecord& e) {
        return e.kind == "reregister";
    }));
    store->reset();  // The next commands open it for writing.

    const auto unknown = run_cli("session register " + quoted() + " --scan 99");
    EXPECT_EQ(unknown.exit_code, 1);
    EXPECT_TRUE(contains(unknown.output, "no scan 99")) << unknown.output;
    ASSERT_EQ(run_cli("session exclude " + quoted() + " 3").exit_code, 0);
    const auto excluded = run_cli("session register " + quoted() + " --scan 3");
    EXPECT_EQ(excluded.exit_code, 1);
    EXPECT_TRUE(contains(excluded.output, "excluded")) << excluded.output;
}

TEST_F(SessionCli, CheckNamesATruncatedFileAndRepairFlagsIt) {
    EXPECT_EQ(run_cli("session check " + quoted()).exit_code, 0);
    const fs::path file = session_ / "scans/scan_000002.ply";
    fs::resize_file(file, fs::file_size(file) - 100);
    const auto found = run_cli("session check " + quoted());
    EXPECT_EQ(found.exit_code, 1) << found.output;
    EXPECT_TRUE(contains(found.output, file.string())) << found.output;
    EXPECT_TRUE(contains(found.output, "damaged-file")) << found.output;
    const auto repaired = run_cli("session check " + quoted() + " --repair");
    EXPECT_EQ(repaired.exit_code, 0) << repaired.output;
    EXPECT_TRUE(contains(repaired.output, "repaired")) << repaired.output;
    EXPECT_TRUE(fs::exists(file));
    EXPECT_EQ(info()["scans"][1]["state"], "failed");
    EXPECT_EQ(run_cli("session check " + quoted()).exit_code, 0);
}

TEST_F(SessionCli, ExportMergesRegisteredScansAndWritesAConf) {
    ASSERT_EQ(run_cli("session exclude " + quoted() + " 1").exit_code, 0);
    const fs::path out = dir_ / "model.ply";
    const fs::path conf = dir_ / "out" / "poses.conf";
    fs::create_directories(conf.parent_path());
    const auto run = run_cli("session export " + quoted() + " --out " + out.string() + " --poses " +
                             conf.string());
    ASSERT_EQ(run.exit_code, 0) << run.output;
    auto model = io::read_ply(out);
    ASSERT_TRUE(model) << model.error().message;
    EXPECT_EQ(model->cloud.size(), 200u + 300u);  // Scans 2 and 3; 1 excluded, 4 failed.
    auto poses = io::read_conf(conf);
    ASSERT_TRUE(poses) << poses.error().message;
    ASSERT_EQ(poses->entries.size(), 2u);
    EXPECT_EQ(poses->entries[0].file, "../stone-1/scans/scan_000002.ply");
    EXPECT_TRUE(poses->entries[1].T_world_scan.isApprox(make_test_pose(3), 1e-12));
    EXPECT_TRUE(fs::exists(conf.parent_path() / poses->entries[0].file));
    // The conf is usable by `assemble`.
    EXPECT_EQ(run_cli("-q assemble " + conf.string()).exit_code, 0);
}

TEST_F(SessionCli, ExportTruthPosesWritesTheTruePosesForEval) {
    const fs::path truth = session_ / "truth.conf";
    const auto run = run_cli("session export " + quoted() + " --truth-poses " + truth.string());
    ASSERT_EQ(run.exit_code, 0) << run.output;
    auto poses = io::read_conf(truth);
    ASSERT_TRUE(poses) << poses.error().message;
    ASSERT_EQ(poses->entries.size(), 1u);                        // Only scan 3 has a true pose.
    EXPECT_EQ(poses->entries[0].file, "scans/scan_000003.ply");  // As `register scans/*.ply`.
    EXPECT_TRUE(poses->entries[0].T_world_scan.isApprox(make_test_pose(3), 1e-12));
    // `anascan eval` reads it: the truth against itself.
    const auto eval = run_cli("eval " + truth.string() + " --truth " + truth.string());
    EXPECT_EQ(eval.exit_code, 0) << eval.output;
    EXPECT_TRUE(contains(eval.output, "placed 1 of 1")) << eval.output;
    const auto neither = run_cli("session export " + quoted());
    EXPECT_EQ(neither.exit_code, 1);
    EXPECT_TRUE(contains(neither.output, "--truth-poses")) << neither.output;
}

TEST_F(SessionCli, ExportTruthPosesOfARealSessionIsAnError) {
    auto store = SessionStore::open(dir_ / "real", SessionOpenMode::kCreateOrOpen);
    ASSERT_TRUE(store) << store.error().message;
    ASSERT_TRUE((*store)->save_scan(make_scan(100u, 1), std::nullopt));
    store->reset();
    const auto run = run_cli("session export " + (dir_ / "real").string() + " --truth-poses " +
                             (dir_ / "t.conf").string());
    EXPECT_EQ(run.exit_code, 1);
    EXPECT_TRUE(contains(run.output, "no scan has a true pose")) << run.output;
    EXPECT_FALSE(fs::exists(dir_ / "t.conf"));
}

TEST_F(SessionCli, ErrorsNameTheFolder) {
    const auto missing = run_cli("session info " + (dir_ / "nothing").string());
    EXPECT_EQ(missing.exit_code, 1);
    EXPECT_TRUE(contains(missing.output, (dir_ / "nothing").string())) << missing.output;
    EXPECT_TRUE(contains(missing.output, "not a session folder")) << missing.output;
    const auto help = run_cli("session export --help");
    EXPECT_EQ(help.exit_code, 0);
    EXPECT_TRUE(contains(help.output, "--voxel-mm"));
}

}  // namespace
}  // namespace anascan
