// `anascan session info|check|export|exclude|note|turned-over` on a session written through
// the store, as a user runs them.
#include <gtest/gtest.h>

#include <nlohmann/json.hpp>

#include "anascan/acquisition/store/session_store.hpp"
#include "anascan/processing/core/pose.hpp"
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
    EXPECT_TRUE(
        contains(run.output, "4 scans (3 registered, 0 flagged, 1 failed, 0 queued, 0 excluded)"))
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
    const auto run = run_cli("session export " + quoted() + " --frame group --out " + out.string() +
                             " --poses " + conf.string());
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

// The default export frame: the stone upright on its ground at the origin, the poses moved
// with the model (the .conf still assembles the same model).
TEST_F(SessionCli, ExportDefaultsToAStoneCentredGroundAlignedFrame) {
    // A 0.3 m box-like stone on a 2 x 2 m ground plane, tilted and 1 m away in scan 1's frame.
    PointCloud ground_and_stone;
    for (int i = 0; i < 80; ++i)
        for (int j = 0; j < 80; ++j)
            ground_and_stone.positions.emplace_back(-1.0f + 0.025f * i, -1.0f + 0.025f * j, 0.0f);
    for (int i = 0; i < 30; ++i)
        for (int j = 0; j < 20; ++j) {
            ground_and_stone.positions.emplace_back(-0.15f + 0.01f * i, -0.1f + 0.01f * j, 0.2f);
            ground_and_stone.positions.emplace_back(-0.15f + 0.01f * i, -0.1f, 0.01f * j);
        }
    const Pose T_scan_true = Pose(Eigen::Translation3d(0.3, -0.2, 1.0) *
                                  Eigen::AngleAxisd(0.5, Eigen::Vector3d(1, 2, 0).normalized()));
    const fs::path session = dir_ / "tilted";
    {
        auto store = SessionStore::open(session, SessionOpenMode::kCreateOrOpen);
        ASSERT_TRUE(store) << store.error().message;
        Scan scan;
        scan.cloud = transformed(ground_and_stone, T_scan_true);
        scan.meta.device_id = "sim:test#0";
        ASSERT_TRUE((*store)->save_scan(scan, std::nullopt));
        ASSERT_TRUE((*store)->record_registration(
            1, {ScanState::kRegistered, 0, Pose::Identity(), "{}", 0.01}));
    }
    const fs::path out = dir_ / "stone.ply";
    const auto run = run_cli("session export " + session.string() + " --out " + out.string());
    ASSERT_EQ(run.exit_code, 0) << run.output;
    EXPECT_TRUE(contains(run.output, "stone frame: +z up")) << run.output;
    auto model = io::read_ply(out);
    ASSERT_TRUE(model) << model.error().message;
    Eigen::Vector3d top_sum = Eigen::Vector3d::Zero();
    std::size_t top = 0, below = 0;
    for (std::size_t i = 0; i < model->cloud.size(); ++i) {
        const Eigen::Vector3d p = model->cloud.world_position(i);
        if (p.z() < -0.005) ++below;
        if (p.z() > 0.195) top_sum += p, ++top;
    }
    EXPECT_EQ(below, 0u) << "the ground is not at z = 0 with the stone above it";
    ASSERT_EQ(top, 600u) << "the stone's top face is not at z = 0.2 m";
    // The origin is under the centroid of the stone's points (top and one side face here),
    // within the stone's half-width of its top's centre.
    EXPECT_LT((top_sum / double(top)).head<2>().norm(), 0.08) << "not centred on the stone";
}

// One scan of a box-like stone on the ground, from one side: the plan says where to scan
// next, with a gain, and the JSON holds the same.
TEST_F(SessionCli, CoverageNextSaysWhereToScanNext) {
    PointCloud cloud;
    for (int i = 0; i < 200; ++i)
        for (int j = 0; j < 200; ++j)
            cloud.positions.emplace_back(-1.0f + 0.01f * i, -1.0f + 0.01f * j, 0.0f);
    for (int i = 0; i < 120; ++i)
        for (int j = 0; j < 80; ++j) {
            cloud.positions.emplace_back(-0.3f + 0.005f * i, -0.2f + 0.005f * j, 0.4f);  // Top.
            cloud.positions.emplace_back(-0.3f + 0.005f * i, -0.2f, 0.005f * j);         // -y side.
        }
    const Eigen::Vector3d sensor(0.0, -1.2, 1.0);
    const Pose T_world_scan{Eigen::Translation3d(sensor)};
    const fs::path session = dir_ / "one-side";
    {
        auto store = SessionStore::open(session, SessionOpenMode::kCreateOrOpen);
        ASSERT_TRUE(store) << store.error().message;
        Scan scan;
        scan.cloud = transformed(cloud, T_world_scan.inverse());
        scan.meta.device_id = "sim:test#0";
        scan.meta.sensor_origin_scan_m = Eigen::Vector3d::Zero();
        ASSERT_TRUE((*store)->save_scan(scan, std::nullopt));
        ASSERT_TRUE((*store)->record_registration(
            1, {ScanState::kRegistered, 0, T_world_scan, "{}", 0.01}));
    }
    const auto text = run_cli("coverage " + session.string() + " --next");
    ASSERT_EQ(text.exit_code, 0) << text.output;
    EXPECT_TRUE(contains(text.output, "next: ")) << text.output;
    EXPECT_TRUE(contains(text.output, "% coverage")) << text.output;
    const auto json = run_cli("-q coverage " + session.string() + " --next --json");
    ASSERT_EQ(json.exit_code, 0) << json.output;
    const auto doc = nlohmann::json::parse(json.output);
    const auto& next = doc.at("next_view");
    EXPECT_EQ(next.at("advice"), "scan") << next.dump();
    EXPECT_GT(next.at("gain_percent").get<double>(), 1.0);
    EXPECT_TRUE(next.at("stone_frame").at("ground_known").get<bool>());
    // The planned sensor stands above the ground, outside the stone.
    const Eigen::Vector3d planned(next.at("sensor_m")[0], next.at("sensor_m")[1],
                                  next.at("sensor_m")[2]);
    EXPECT_GT(planned.z(), 0.2);
    EXPECT_TRUE(std::abs(planned.x()) > 0.3 || std::abs(planned.y()) > 0.2 || planned.z() > 0.4)
        << planned.transpose();
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

// An archived session copied while it was open (its log not yet merged into the database)
// and then made read-only, as on a CD or a read-only network share: inspection works.
TEST_F(SessionCli, InfoReadsAReadOnlyCopyWithAnUnmergedLog) {
    const fs::path copy = dir_ / "archive";
    {
        auto store = SessionStore::open(dir_ / "open", SessionOpenMode::kCreateOrOpen);
        ASSERT_TRUE(store) << store.error().message;
        for (unsigned i = 1; i <= 3; ++i) ASSERT_TRUE((*store)->save_scan(make_scan(50u, i), {}));
        ASSERT_TRUE(fs::exists(dir_ / "open" / "session.sqlite-wal"));
        fs::copy(dir_ / "open", copy, fs::copy_options::recursive);
        fs::remove(copy / "session.sqlite-shm");
    }
    const fs::path mount = dir_ / "read-only";
    fs::create_directories(mount);
    const std::string bind = "unshare -m sh -c 'mount --bind " + copy.string() + " " +
                             mount.string() + " && mount -o remount,bind,ro " + mount.string() +
                             " && touch " + mount.string() + "/x 2>/dev/null; test ! -e " +
                             mount.string() + "/x && " + std::string(ANASCAN_CLI) +
                             " session info " + mount.string() + " 2>&1; echo exit=$?'";
    const auto probe = testing_util::run_shell("unshare -m sh -c 'mount --bind " + copy.string() +
                                               " " + mount.string() + "' 2>&1");
    if (probe.exit_code != 0)
        GTEST_SKIP() << "cannot make a read-only mount here: " << probe.output;
    const auto run = testing_util::run_shell(bind);
    EXPECT_TRUE(contains(run.output, "exit=0")) << run.output;
    EXPECT_TRUE(contains(run.output, "3 scans (0 registered, 0 flagged, 0 failed, 3 queued"))
        << run.output;
}

TEST_F(SessionCli, ExportLeavesExcludedScansOutOfTheGroupChoice) {
    // Group 0: scans 1-3, group 5: scans 5 and 6. With two of group 0 excluded, group 5
    // is the largest: the export picks it.
    {
        auto store = SessionStore::open(session_, SessionOpenMode::kOpenExisting);
        ASSERT_TRUE(store) << store.error().message;
        for (int i = 5; i <= 6; ++i) {
            ASSERT_TRUE((*store)->save_scan(make_scan(10u * i, i), std::nullopt));
            RegistrationUpdate u{ScanState::kRegistered, 5, make_test_pose(i), "{}", 0.01};
            ASSERT_TRUE((*store)->record_registration(i, u));
        }
    }
    ASSERT_EQ(run_cli("session exclude " + quoted() + " 1").exit_code, 0);
    ASSERT_EQ(run_cli("session exclude " + quoted() + " 2").exit_code, 0);
    const auto run = run_cli("session export " + quoted() + " --out " + (dir_ / "m.ply").string());
    ASSERT_EQ(run.exit_code, 0) << run.output;
    EXPECT_TRUE(contains(run.output, "from 2 scans of group 5")) << run.output;
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
