#include "store/schema.hpp"

#include <array>
#include <chrono>

#include "anascan/acquisition/store/session_store.hpp"

namespace anascan::acquisition::db {
namespace {

// Version 1: the first schema. Never edit a shipped migration; add a new one.
constexpr std::string_view kV1 = R"sql(
CREATE TABLE migrations(version INTEGER PRIMARY KEY, applied_ns INTEGER NOT NULL);
CREATE TABLE devices(id TEXT PRIMARY KEY, kind TEXT NOT NULL, first_seen_ns INTEGER NOT NULL);
CREATE TABLE scans(
    seq INTEGER PRIMARY KEY,
    file TEXT NOT NULL UNIQUE,
    device_id TEXT NOT NULL,
    device_kind TEXT NOT NULL,
    captured_ns INTEGER NOT NULL,
    acknowledged_ns INTEGER NOT NULL,
    settings_json TEXT NOT NULL,
    sensor_origin_m TEXT,
    pose_prior TEXT,
    true_pose TEXT,
    point_count INTEGER NOT NULL,
    state TEXT NOT NULL,
    excluded INTEGER NOT NULL DEFAULT 0,
    grp INTEGER NOT NULL DEFAULT -1,
    pose TEXT,
    quality_json TEXT NOT NULL DEFAULT '',
    latency_s REAL);
CREATE TABLE events(id INTEGER PRIMARY KEY AUTOINCREMENT, time_ns INTEGER NOT NULL,
                    kind TEXT NOT NULL, device TEXT NOT NULL, message TEXT NOT NULL);
CREATE TABLE notes(id INTEGER PRIMARY KEY AUTOINCREMENT, time_ns INTEGER NOT NULL,
                   seq INTEGER, text TEXT NOT NULL);
CREATE TABLE session_values(key TEXT PRIMARY KEY, json TEXT NOT NULL);
)sql";

// Version 2: "stone turned over" marks and the file problem found by `session check`.
constexpr std::string_view kV2 = R"sql(
CREATE TABLE turnovers(after_seq INTEGER PRIMARY KEY, time_ns INTEGER NOT NULL);
ALTER TABLE scans ADD COLUMN file_problem TEXT NOT NULL DEFAULT '';
)sql";

// Version 3: the CRC-32 (zlib) of each scan file's bytes, recorded at acknowledgement, so that
// `session check` finds bit flips and torn writes that still parse. NULL for a scan saved
// before (`session check --repair` records it for a file that is otherwise intact).
constexpr std::string_view kV3 = R"sql(
ALTER TABLE scans ADD COLUMN file_crc32 INTEGER;
)sql";

constexpr std::array<std::string_view, 3> kMigrations = {kV1, kV2, kV3};
static_assert(kMigrations.size() == kSessionSchemaVersion);

Expected<void> apply(Connection& db, int version) {
    auto tx = Transaction::begin(db);
    if (!tx) return fail(tx.error());
    const std::string what = "cannot upgrade the schema to version " + std::to_string(version);
    if (auto ok = db.exec(migration_sql(version), what); !ok) return ok;
    auto insert = Statement::prepare(db, "INSERT INTO migrations(version, applied_ns) VALUES(?,?)");
    if (!insert) return fail(insert.error());
    const auto now = std::chrono::system_clock::now().time_since_epoch();
    insert->bind(1, std::int64_t{version})
        .bind(2, std::int64_t{std::chrono::duration_cast<std::chrono::nanoseconds>(now).count()});
    if (auto ok = insert->run(what); !ok) return ok;
    if (auto ok = db.exec("PRAGMA user_version = " + std::to_string(version), what); !ok) {
        return ok;
    }
    return tx->commit();
}

}  // namespace

std::string_view migration_sql(int version) {
    if (version < 1 || version > static_cast<int>(kMigrations.size())) return {};
    return kMigrations[static_cast<std::size_t>(version - 1)];
}

Expected<int> schema_version(const Connection& db) {
    auto stmt = Statement::prepare(db, "PRAGMA user_version");
    if (!stmt) return fail(stmt.error());
    auto row = stmt->step("cannot read the schema version");
    if (!row) return fail(row.error());
    return *row ? static_cast<int>(stmt->int64(0)) : 0;
}

Expected<void> migrate(Connection& db, bool read_only) {
    auto version = schema_version(db);
    if (!version) return fail(version.error());
    if (*version > kSessionSchemaVersion) {
        return fail(ErrorCode::kUnsupported,
                    db.file().string() + ": the session was written by a newer anascan (schema " +
                        std::to_string(*version) + ", this program knows up to " +
                        std::to_string(kSessionSchemaVersion) + "): update anascan to open it");
    }
    if (*version < kSessionSchemaVersion && read_only) {
        return fail(ErrorCode::kUnsupported,
                    db.file().string() + ": schema version " + std::to_string(*version) +
                        " needs an upgrade to " + std::to_string(kSessionSchemaVersion) +
                        ": run `anascan session check " + db.file().parent_path().string() +
                        " --repair` once (it upgrades the database)");
    }
    for (int v = *version + 1; v <= kSessionSchemaVersion; ++v) {
        if (auto ok = apply(db, v); !ok) return ok;
    }
    return {};
}

}  // namespace anascan::acquisition::db
