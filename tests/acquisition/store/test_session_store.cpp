// The session store: round trips, reopening, exclusion, turn-over marks, locking, schema
// versions and migration from a version-1 database written by hand.
#include <gtest/gtest.h>
#include <sqlite3.h>

#include <fstream>
#include <thread>

#include "anascan/acquisition/store/session_store.hpp"
#include "session_test_support.hpp"

namespace anascan::acquisition {
namespace {

using testing_util::make_scan;
using testing_util::make_test_pose;
using testing_util::SessionFolder;
using SessionStoreTest = SessionFolder;

std::unique_ptr<SessionStore> open_or_die(const std::filesystem::path& dir,
                                          SessionOpenMode mode = SessionOpenMode::kCreateOrOpen) {
    auto store = SessionStore::open(dir, mode);
    EXPECT_TRUE(store.has_value()) << (store ? "" : store.error().message);
    return store ? std::move(*store) : nullptr;
}

void expect_same_pose(const std::optional<Pose>& a, const Pose& b) {
    ASSERT_TRUE(a.has_value());
    EXPECT_EQ(a->matrix(), b.matrix());  // %.17g text round-trips exactly.
}

void exec_sql(const std::filesystem::path& file, const std::string& sql) {
    sqlite3* db = nullptr;
    ASSERT_EQ(sqlite3_open(file.c_str(), &db), SQLITE_OK);
    char* message = nullptr;
    const int rc = sqlite3_exec(db, sql.c_str(), nullptr, nullptr, &message);
    EXPECT_EQ(rc, SQLITE_OK) << (message ? message : "");
    sqlite3_free(message);
    sqlite3_close(db);
}

// Writes three scans with poses, states, an event, notes and values.
void write_session(const std::filesystem::path& dir, const Scan& first) {
    auto store = open_or_die(dir);
    ASSERT_TRUE(store);
    Scan with_prior = first;
    with_prior.meta.T_world_scan = make_test_pose(7);
    auto r1 = store->save_scan(with_prior, make_test_pose(1));
    ASSERT_TRUE(r1) << r1.error().message;
    EXPECT_EQ(r1->seq, 1);
    EXPECT_EQ(r1->file, "scans/scan_000001.ply");
    ASSERT_TRUE(store->save_scan(make_scan(50, 2, "sim:other#1"), std::nullopt));
    ASSERT_TRUE(store->save_scan(make_scan(10, 3), make_test_pose(3)));
    ASSERT_TRUE(store->record_registration(
        1, {ScanState::kRegistered, 0, Pose::Identity(), R"({"rms_m":0.0001})", 0.25}));
    ASSERT_TRUE(store->record_registration(2, {ScanState::kFailed, -1, {}, "{}", {}}));
    ASSERT_TRUE(store->update_poses({{1, {0, make_test_pose(4)}}, {3, {1, make_test_pose(5)}}}));
    ASSERT_TRUE(store->add_event("device-error", "sim:test#0", "unplugged"));
    ASSERT_TRUE(store->add_note(2, "smudge on the lens"));
    ASSERT_TRUE(store->add_note(std::nullopt, "rain started"));
    ASSERT_TRUE(store->set_value("coverage", R"({"fraction":0.5})"));
    ASSERT_TRUE(store->set_value("coverage", R"({"fraction":0.75})"));
}

void expect_scan_records(SessionStore& store, const Scan& first) {
    auto scans = store.scans();
    ASSERT_TRUE(scans) << scans.error().message;
    ASSERT_EQ(scans->size(), 3u);
    const ScanRecord& s1 = (*scans)[0];
    EXPECT_EQ(s1.state, ScanState::kRegistered);
    EXPECT_EQ(s1.group, 0);
    expect_same_pose(s1.pose, make_test_pose(4));
    expect_same_pose(s1.true_pose, make_test_pose(1));
    expect_same_pose(s1.pose_prior, make_test_pose(7));
    EXPECT_EQ(s1.quality_json, R"({"rms_m":0.0001})");
    ASSERT_TRUE(s1.latency_s);
    EXPECT_DOUBLE_EQ(*s1.latency_s, 0.25);
    EXPECT_EQ(s1.point_count, 300u);
    EXPECT_EQ(s1.device_id, "sim:test#0");
    EXPECT_EQ(s1.device_kind, DeviceKind::kStructuredLight);
    EXPECT_EQ(s1.settings_json, first.meta.settings_json);
    EXPECT_EQ(s1.captured_at, first.meta.time);
    EXPECT_LE(s1.captured_at, s1.acknowledged_at);
    EXPECT_EQ(*s1.sensor_origin_scan_m, *first.meta.sensor_origin_scan_m);
    EXPECT_EQ((*scans)[1].state, ScanState::kFailed);
    EXPECT_FALSE((*scans)[1].pose);
    EXPECT_FALSE((*scans)[1].true_pose);
    EXPECT_FALSE((*scans)[1].latency_s);
    EXPECT_EQ((*scans)[2].group, 1);
    EXPECT_EQ((*scans)[2].state, ScanState::kQueued);
}

void expect_scan_file(SessionStore& store, const Scan& first) {
    auto loaded = store.load_scan(1);
    ASSERT_TRUE(loaded) << loaded.error().message;
    EXPECT_EQ(loaded->cloud.origin_m, first.cloud.origin_m);
    EXPECT_EQ(loaded->cloud.positions, first.cloud.positions);
    EXPECT_EQ(loaded->cloud.normals, first.cloud.normals);
    EXPECT_EQ(loaded->cloud.intensity, first.cloud.intensity);
    EXPECT_EQ(loaded->cloud.confidence, first.cloud.confidence);
    EXPECT_EQ(loaded->meta.sequence, 1);
    EXPECT_EQ(*loaded->meta.sensor_origin_scan_m, *first.meta.sensor_origin_scan_m);
    expect_same_pose(loaded->meta.T_world_scan, make_test_pose(4));
}

void expect_events_notes_values(SessionStore& store) {
    auto events = store.events();
    ASSERT_TRUE(events);
    ASSERT_EQ(events->size(), 1u);
    EXPECT_EQ((*events)[0].kind, "device-error");
    EXPECT_EQ((*events)[0].device, "sim:test#0");
    auto notes = store.notes();
    ASSERT_TRUE(notes);
    ASSERT_EQ(notes->size(), 2u);
    EXPECT_EQ((*notes)[0].seq, std::optional<std::int64_t>(2));
    EXPECT_EQ((*notes)[1].text, "rain started");
    EXPECT_FALSE((*notes)[1].seq);
    auto devices = store.devices();
    ASSERT_TRUE(devices);
    EXPECT_EQ(devices->size(), 2u);
    auto coverage = store.value("coverage");
    ASSERT_TRUE(coverage);
    EXPECT_EQ(**coverage, R"({"fraction":0.75})");
    EXPECT_FALSE(*store.value("nothing"));
    // Read-only: writes are refused.
    EXPECT_FALSE(store.add_note(std::nullopt, "x"));
    EXPECT_FALSE(store.save_scan(make_scan(5, 9), std::nullopt));
}

TEST_F(SessionStoreTest, ScansPosesEventsNotesAndValuesSurviveReopening) {
    const Scan first = make_scan(300, 1);
    write_session(dir_, first);
    if (HasFatalFailure()) return;
    auto store = open_or_die(dir_, SessionOpenMode::kReadOnly);
    ASSERT_TRUE(store);
    expect_scan_records(*store, first);
    expect_scan_file(*store, first);
    expect_events_notes_values(*store);
}

TEST_F(SessionStoreTest, ExclusionIsUndoableAndTurnOverFlagsTheNextScan) {
    auto store = open_or_die(dir_);
    ASSERT_TRUE(store);
    for (unsigned i = 0; i < 3; ++i) ASSERT_TRUE(store->save_scan(make_scan(20, i), std::nullopt));
    ASSERT_TRUE(
        store->record_registration(2, {ScanState::kRegistered, 0, Pose::Identity(), "{}", 0.1}));
    ASSERT_TRUE(store->set_excluded(2, true));
    EXPECT_EQ(store->scan(2)->state, ScanState::kExcluded);
    EXPECT_TRUE(store->scan(2)->excluded);
    ASSERT_TRUE(store->set_excluded(2, false));
    EXPECT_EQ(store->scan(2)->state, ScanState::kRegistered);  // Back to what it was.
    ASSERT_TRUE(store->mark_turned_over(2));
    EXPECT_FALSE(store->scan(2)->turned_over_before);
    EXPECT_TRUE(store->scan(3)->turned_over_before);
    auto missing = store->set_excluded(42, true);
    ASSERT_FALSE(missing);
    EXPECT_NE(missing.error().message.find("no scan 42"), std::string::npos);
    EXPECT_FALSE(store->add_note(42, "about nothing"));
    EXPECT_FALSE(store->record_registration(42, {}));
}

TEST_F(SessionStoreTest, ConcurrentSavesAndUpdatesKeepDenseSequenceNumbers) {
    auto store = open_or_die(dir_);
    ASSERT_TRUE(store);
    auto saver = [&](unsigned seed) {
        for (unsigned i = 0; i < 8; ++i) {
            auto saved = store->save_scan(make_scan(30, seed + i), std::nullopt);
            EXPECT_TRUE(saved) << saved.error().message;
            if (saved) {
                EXPECT_TRUE(store->record_registration(
                    saved->seq, {ScanState::kRegistered, 0, make_test_pose(1), "{}", 0.01}));
            }
        }
    };
    std::thread a(saver, 100u), b(saver, 200u);
    std::thread c([&] {
        for (int i = 0; i < 8; ++i) EXPECT_TRUE(store->add_event("tick", "", "x"));
    });
    a.join();
    b.join();
    c.join();
    auto scans = store->scans();
    ASSERT_TRUE(scans);
    ASSERT_EQ(scans->size(), 16u);
    for (std::size_t i = 0; i < scans->size(); ++i) {
        EXPECT_EQ((*scans)[i].seq, static_cast<std::int64_t>(i + 1));
        EXPECT_EQ((*scans)[i].state, ScanState::kRegistered);
        EXPECT_TRUE(store->load_scan((*scans)[i].seq));
    }
    EXPECT_EQ(store->events()->size(), 8u);
}

TEST_F(SessionStoreTest, ASecondWriterIsRefusedButReadersAreNot) {
    auto writer = open_or_die(dir_);
    ASSERT_TRUE(writer);
    ASSERT_TRUE(writer->save_scan(make_scan(10, 1), std::nullopt));
    auto second = SessionStore::open(dir_, SessionOpenMode::kOpenExisting);
    ASSERT_FALSE(second);
    EXPECT_EQ(second.error().code, ErrorCode::kBusy);
    EXPECT_NE(second.error().message.find(dir_.string()), std::string::npos);
    auto reader = open_or_die(dir_, SessionOpenMode::kReadOnly);
    ASSERT_TRUE(reader);
    EXPECT_EQ(reader->scans()->size(), 1u);
}

TEST_F(SessionStoreTest, OpeningWhatIsNotASessionNamesTheFolder) {
    auto missing = SessionStore::open(dir_ / "nowhere", SessionOpenMode::kOpenExisting);
    ASSERT_FALSE(missing);
    EXPECT_NE(missing.error().message.find("nowhere"), std::string::npos);
    EXPECT_NE(missing.error().message.find("not a session folder"), std::string::npos);
    std::ofstream(root_ / "plain-file") << "x";
    auto file = SessionStore::open(root_ / "plain-file", SessionOpenMode::kCreateOrOpen);
    ASSERT_FALSE(file);
    EXPECT_NE(file.error().message.find("plain-file"), std::string::npos);
}

TEST_F(SessionStoreTest, ACorruptDatabaseIsReportedWithWhatToDo) {
    std::filesystem::create_directories(dir_ / "scans");
    std::ofstream(dir_ / "session.sqlite") << std::string(8192, 'x');
    auto store = SessionStore::open(dir_, SessionOpenMode::kOpenExisting);
    ASSERT_FALSE(store);
    EXPECT_NE(store.error().message.find("session.sqlite"), std::string::npos);
    EXPECT_NE(store.error().message.find("session check"), std::string::npos)
        << store.error().message;
}

TEST_F(SessionStoreTest, AnEmptyDatabaseIsMigratedStepByStep) {
    std::filesystem::create_directories(dir_);
    exec_sql(dir_ / "session.sqlite", "PRAGMA user_version = 0");
    auto store = open_or_die(dir_, SessionOpenMode::kOpenExisting);
    ASSERT_TRUE(store);
    auto saved = store->save_scan(make_scan(10, 1), std::nullopt);
    EXPECT_TRUE(saved) << saved.error().message;
    store.reset();
    sqlite3* db = nullptr;
    ASSERT_EQ(sqlite3_open((dir_ / "session.sqlite").c_str(), &db), SQLITE_OK);
    sqlite3_stmt* stmt = nullptr;
    sqlite3_prepare_v2(db, "SELECT group_concat(version) FROM migrations", -1, &stmt, nullptr);
    ASSERT_EQ(sqlite3_step(stmt), SQLITE_ROW);
    EXPECT_STREQ(reinterpret_cast<const char*>(sqlite3_column_text(stmt, 0)), "1,2");
    sqlite3_finalize(stmt);
    sqlite3_prepare_v2(db, "PRAGMA user_version", -1, &stmt, nullptr);
    ASSERT_EQ(sqlite3_step(stmt), SQLITE_ROW);
    EXPECT_EQ(sqlite3_column_int(stmt, 0), kSessionSchemaVersion);
    sqlite3_finalize(stmt);
    sqlite3_close(db);
}

TEST_F(SessionStoreTest, ANewerSchemaIsRefusedClearly) {
    ASSERT_TRUE(open_or_die(dir_));
    exec_sql(dir_ / "session.sqlite", "PRAGMA user_version = 99");
    auto store = SessionStore::open(dir_, SessionOpenMode::kOpenExisting);
    ASSERT_FALSE(store);
    EXPECT_EQ(store.error().code, ErrorCode::kUnsupported);
    EXPECT_NE(store.error().message.find("newer anascan"), std::string::npos);
    EXPECT_NE(store.error().message.find("session.sqlite"), std::string::npos);
}

// The version-1 schema as it shipped, written by hand (not through the migration code).
constexpr const char* kVersion1Database = R"sql(
CREATE TABLE migrations(version INTEGER PRIMARY KEY, applied_ns INTEGER NOT NULL);
CREATE TABLE devices(id TEXT PRIMARY KEY, kind TEXT NOT NULL, first_seen_ns INTEGER NOT NULL);
CREATE TABLE scans(seq INTEGER PRIMARY KEY, file TEXT NOT NULL UNIQUE, device_id TEXT NOT NULL,
    device_kind TEXT NOT NULL, captured_ns INTEGER NOT NULL, acknowledged_ns INTEGER NOT NULL,
    settings_json TEXT NOT NULL, sensor_origin_m TEXT, pose_prior TEXT, true_pose TEXT,
    point_count INTEGER NOT NULL, state TEXT NOT NULL, excluded INTEGER NOT NULL DEFAULT 0,
    grp INTEGER NOT NULL DEFAULT -1, pose TEXT, quality_json TEXT NOT NULL DEFAULT '',
    latency_s REAL);
CREATE TABLE events(id INTEGER PRIMARY KEY AUTOINCREMENT, time_ns INTEGER NOT NULL,
    kind TEXT NOT NULL, device TEXT NOT NULL, message TEXT NOT NULL);
CREATE TABLE notes(id INTEGER PRIMARY KEY AUTOINCREMENT, time_ns INTEGER NOT NULL, seq INTEGER,
    text TEXT NOT NULL);
CREATE TABLE session_values(key TEXT PRIMARY KEY, json TEXT NOT NULL);
INSERT INTO migrations VALUES(1, 1700000000000000000);
INSERT INTO devices VALUES('sim:old#0', 'time-of-flight', 1700000000000000000);
INSERT INTO scans(seq, file, device_id, device_kind, captured_ns, acknowledged_ns, settings_json,
    point_count, state, grp, pose, latency_s)
    VALUES(1, 'scans/scan_000001.ply', 'sim:old#0', 'time-of-flight', 1700000000000000000,
           1700000000500000000, '{}', 0, 'registered', 0,
           '1 0 0 0.5 0 1 0 0 0 0 1 0 0 0 0 1', 0.125);
PRAGMA user_version = 1;
)sql";

TEST_F(SessionStoreTest, AVersion1DatabaseIsUpgradedKeepingItsRows) {
    std::filesystem::create_directories(dir_ / "scans");
    exec_sql(dir_ / "session.sqlite", kVersion1Database);
    auto old = SessionStore::open(dir_, SessionOpenMode::kReadOnly);
    ASSERT_FALSE(old);  // Read-only cannot upgrade; it says how.
    EXPECT_NE(old.error().message.find("--repair"), std::string::npos);
    auto store = open_or_die(dir_, SessionOpenMode::kOpenExisting);
    ASSERT_TRUE(store);
    auto scans = store->scans();
    ASSERT_TRUE(scans) << scans.error().message;
    ASSERT_EQ(scans->size(), 1u);
    EXPECT_EQ((*scans)[0].device_kind, DeviceKind::kTimeOfFlight);
    EXPECT_EQ((*scans)[0].state, ScanState::kRegistered);
    ASSERT_TRUE((*scans)[0].pose);
    EXPECT_EQ((*scans)[0].pose->translation().x(), 0.5);
    EXPECT_EQ((*scans)[0].latency_s, std::optional<double>(0.125));
    EXPECT_TRUE((*scans)[0].file_problem.empty());
    ASSERT_TRUE(store->mark_turned_over(1));  // Version-2 table.
    auto saved = store->save_scan(make_scan(5, 1), std::nullopt);
    ASSERT_TRUE(saved) << saved.error().message;
    EXPECT_EQ(saved->seq, 2);
    EXPECT_TRUE(store->scan(2)->turned_over_before);
}

}  // namespace
}  // namespace anascan::acquisition
