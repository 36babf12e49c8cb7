// libFuzzer harness for the session database's contents: a valid session (two scans, a
// registration, an event, a note, a value, a turn-over) is written once; each input then
// rewrites, copies or deletes rows of any table of a fresh copy, with hostile values of any
// SQLite type, and the copy is opened read-only, listed, loaded, shown as JSON and checked,
// with and without repair. Nothing may crash, leak or hang; every error carries a message.
// The input is a sequence of edits: [table][op][row][column] and, for an update,
// [type][length][bytes...].
#include <sqlite3.h>
#include <unistd.h>

#include <cstddef>
#include <cstdint>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <map>
#include <span>
#include <string>
#include <vector>

#include "anascan/acquisition/store/session_check.hpp"
#include "anascan/acquisition/store/session_json.hpp"
#include "anascan/acquisition/store/session_store.hpp"

namespace {

namespace fs = std::filesystem;
using namespace anascan;
using namespace anascan::acquisition;

using FileImage = std::map<fs::path, std::string>;  // relative path -> bytes

void require(bool condition) {
    if (!condition) std::abort();
}

template <typename T>
void require_message(const Expected<T>& result) {
    if (!result) require(!result.error().message.empty());
}

Scan small_scan(unsigned seed) {
    Scan scan;
    scan.meta.device_id = "sim:structured-light#0";
    scan.meta.device_kind = DeviceKind::kStructuredLight;
    scan.meta.sensor_origin_scan_m = Eigen::Vector3d(0, 0, 1);
    for (unsigned i = 0; i < 40; ++i)
        scan.cloud.positions.emplace_back(0.01f * float(i % 7), 0.01f * float(i / 7),
                                          0.001f * float(seed));
    return scan;
}

void write_template(const fs::path& dir) {
    auto store = SessionStore::open(dir, SessionOpenMode::kCreateOrOpen);
    require(bool(store));
    SessionStore& s = **store;
    require(bool(s.save_scan(small_scan(1), Pose::Identity())));
    require(bool(s.save_scan(small_scan(2), std::nullopt)));
    RegistrationUpdate update;
    update.group = 0;
    update.pose = Pose::Identity();
    update.quality_json = R"({"rms_mm":0.1,"overlap":0.9})";
    update.latency_s = 0.5;
    require(bool(s.record_registration(1, update)));
    require(bool(s.add_event("merge", "sim:structured-light#0", "groups 1 and 0 merged")));
    require(bool(s.add_note(2, "chipped corner")));
    require(bool(s.set_value("coverage", R"({"fraction":0.5,"area_m2":0.2})")));
    require(bool(s.mark_turned_over(1)));
    require(bool(s.checkpoint()));
}

FileImage read_tree(const fs::path& dir) {
    FileImage image;
    for (const auto& entry : fs::recursive_directory_iterator(dir)) {
        if (!entry.is_regular_file()) continue;
        std::ifstream in(entry.path(), std::ios::binary);
        image[fs::relative(entry.path(), dir)] =
            std::string(std::istreambuf_iterator<char>(in), {});
    }
    return image;
}

void write_tree(const fs::path& dir, const FileImage& image) {
    fs::remove_all(dir);
    for (const auto& [relative, bytes] : image) {
        fs::create_directories((dir / relative).parent_path());
        std::ofstream(dir / relative, std::ios::binary) << bytes;
    }
}

struct Workspace {
    fs::path root, work;
    FileImage image;
};

const Workspace& workspace() {
    static const Workspace w = [] {
        Workspace made;
        made.root =
            fs::temp_directory_path() / ("anascan-fuzz-session-" + std::to_string(getpid()));
        fs::remove_all(made.root);
        write_template(made.root / "template");
        made.image = read_tree(made.root / "template");
        fs::remove_all(made.root / "template");  // hostile file names cannot reach it
        made.work = made.root / "work";
        return made;
    }();
    // Registered after `w` is made, so it runs before `w` is destroyed.
    static const bool removed_at_exit = (std::atexit([] {
                                             std::error_code ec;
                                             fs::remove_all(workspace().root, ec);
                                         }),
                                         true);
    (void)removed_at_exit;
    return w;
}

struct Table {
    std::string name;
    std::vector<std::string> columns;
};

std::vector<Table> tables(sqlite3* db) {
    std::vector<Table> out;
    sqlite3_stmt* st = nullptr;
    sqlite3_prepare_v2(db, "SELECT name FROM sqlite_master WHERE type='table' ORDER BY name", -1,
                       &st, nullptr);
    while (sqlite3_step(st) == SQLITE_ROW)
        out.push_back({reinterpret_cast<const char*>(sqlite3_column_text(st, 0)), {}});
    sqlite3_finalize(st);
    for (Table& t : out) {
        sqlite3_prepare_v2(db, ("PRAGMA table_info(\"" + t.name + "\")").c_str(), -1, &st, nullptr);
        while (sqlite3_step(st) == SQLITE_ROW)
            t.columns.emplace_back(reinterpret_cast<const char*>(sqlite3_column_text(st, 1)));
        sqlite3_finalize(st);
    }
    return out;
}

/// Reads the input front to back; past its end every byte reads as 0.
struct Reader {
    std::span<const std::uint8_t> data;
    std::uint8_t byte() {
        if (data.empty()) return 0;
        const std::uint8_t b = data[0];
        data = data.subspan(1);
        return b;
    }
    std::string bytes(std::size_t n) {
        n = std::min(n, data.size());
        std::string s(reinterpret_cast<const char*>(data.data()), n);
        data = data.subspan(n);
        return s;
    }
};

void bind_value(sqlite3_stmt* st, int index, Reader& in) {
    const int type = in.byte() % 5;
    const std::string raw = in.bytes(type < 3 ? 8 : in.byte());
    std::int64_t i = 0;
    double d = 0;
    std::memcpy(&i, raw.data(), std::min(raw.size(), sizeof i));
    std::memcpy(&d, raw.data(), std::min(raw.size(), sizeof d));
    if (type == 0) sqlite3_bind_null(st, index);
    if (type == 1) sqlite3_bind_int64(st, index, i);
    if (type == 2) sqlite3_bind_double(st, index, d);
    if (type == 3) sqlite3_bind_text(st, index, raw.data(), int(raw.size()), SQLITE_TRANSIENT);
    if (type == 4) sqlite3_bind_blob(st, index, raw.data(), int(raw.size()), SQLITE_TRANSIENT);
}

/// One edit: update a cell, copy a row with one cell changed, or delete a row.
void apply_edit(sqlite3* db, const Table& table, Reader& in) {
    const int op = in.byte() % 3;
    const std::string row = std::to_string(in.byte() % 4);
    const std::string& column = table.columns[in.byte() % table.columns.size()];
    const std::string pick =
        "(SELECT rowid FROM \"" + table.name + "\" LIMIT 1 OFFSET " + row + ")";
    std::string sql;
    if (op == 0)
        sql = "UPDATE \"" + table.name + "\" SET \"" + column + "\"=?1 WHERE rowid=" + pick;
    if (op == 1)
        sql = "INSERT OR IGNORE INTO \"" + table.name + "\" SELECT * FROM \"" + table.name +
              "\" WHERE rowid=" + pick;
    if (op == 2) sql = "DELETE FROM \"" + table.name + "\" WHERE rowid=" + pick;
    sqlite3_stmt* st = nullptr;
    if (sqlite3_prepare_v2(db, sql.c_str(), -1, &st, nullptr) == SQLITE_OK) {
        if (op == 0) bind_value(st, 1, in);
        sqlite3_step(st);
    }
    sqlite3_finalize(st);
}

void edit_database(const fs::path& file, Reader in) {
    sqlite3* db = nullptr;
    require(sqlite3_open(file.c_str(), &db) == SQLITE_OK);
    const std::vector<Table> all = tables(db);
    for (int edits = 0; !in.data.empty() && edits < 16 && !all.empty(); ++edits)
        apply_edit(db, all[in.byte() % all.size()], in);
    sqlite3_close(db);
}

void read_everything(const fs::path& dir) {
    auto store = SessionStore::open(dir, SessionOpenMode::kReadOnly);
    require_message(store);
    if (!store) return;
    const SessionStore& s = **store;
    const auto scans = s.scans();
    require_message(scans);
    if (scans) {
        for (const ScanRecord& r : *scans) require_message(s.load_scan(r.seq));
    }
    require_message(s.events());
    require_message(s.notes());
    require_message(s.devices());
    require_message(s.value("coverage"));
    require_message(session_info_json(s));
    require_message(coverage_fraction(s));
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    const Workspace& w = workspace();
    write_tree(w.work, w.image);
    edit_database(w.work / "session.sqlite", Reader{{data, size}});
    read_everything(w.work);
    require_message(check_session(w.work));
    require_message(check_session(w.work, {.repair = true}));
    read_everything(w.work);
    return 0;
}
