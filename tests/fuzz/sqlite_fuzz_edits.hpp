#pragma once
// Shared by the fuzz harnesses of the SQLite stores (session, campaign): a template folder
// written once and copied for each input, and hostile edits of any table's rows (update a
// cell with a value of any SQLite type, copy a row, delete a row).
// The input is a sequence of edits: [table][op][row][column] and, for an update,
// [type][length][bytes...].
#include <sqlite3.h>
#include <unistd.h>

#include <algorithm>
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

#include "fuzz_require.hpp"

namespace anascan::fuzz {

namespace fs = std::filesystem;

using FileImage = std::map<fs::path, std::string>;  // relative path -> bytes

inline FileImage read_tree(const fs::path& dir) {
    FileImage image;
    for (const auto& entry : fs::recursive_directory_iterator(dir)) {
        if (!entry.is_regular_file()) continue;
        std::ifstream in(entry.path(), std::ios::binary);
        image[fs::relative(entry.path(), dir)] =
            std::string(std::istreambuf_iterator<char>(in), {});
    }
    return image;
}

inline void write_tree(const fs::path& dir, const FileImage& image) {
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

/// The template written once by `write_template` into a per-process temporary folder, kept as
/// bytes (so hostile file names cannot reach it), and the folder each input works in.
inline const Workspace& workspace(const std::string& name = {},
                                  void (*write_template)(const fs::path&) = nullptr) {
    static const Workspace w = [&] {
        Workspace made;
        made.root =
            fs::temp_directory_path() / ("anascan-fuzz-" + name + "-" + std::to_string(getpid()));
        fs::remove_all(made.root);
        write_template(made.root / "template");
        made.image = read_tree(made.root / "template");
        fs::remove_all(made.root / "template");
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

inline std::vector<Table> tables(sqlite3* db) {
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

inline void bind_value(sqlite3_stmt* st, int index, Reader& in) {
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
inline void apply_edit(sqlite3* db, const Table& table, Reader& in) {
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

inline void edit_database(const fs::path& file, Reader in) {
    sqlite3* db = nullptr;
    require(sqlite3_open(file.c_str(), &db) == SQLITE_OK);
    const std::vector<Table> all = tables(db);
    for (int edits = 0; !in.data.empty() && edits < 16 && !all.empty(); ++edits)
        apply_edit(db, all[in.byte() % all.size()], in);
    sqlite3_close(db);
}

}  // namespace anascan::fuzz
