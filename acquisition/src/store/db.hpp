#pragma once
// A thin RAII layer over the SQLite C API for the session store: a connection, prepared
// statements with typed binds/columns, and errors that name the database file and say
// what to do.
#include <sqlite3.h>

#include <cstdint>
#include <filesystem>
#include <optional>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include "anascan/processing/core/expected.hpp"

namespace anascan::acquisition::db {

/// Error for SQLite result `rc` on `db` while doing `what`; names `file`, adds advice.
Error sqlite_error(sqlite3* db, int rc, const std::filesystem::path& file, std::string_view what);

class Connection {
public:
    Connection() = default;
    ~Connection();
    Connection(const Connection&) = delete;
    Connection& operator=(const Connection&) = delete;

    /// Opens (or creates when `create`) the database; `read_only` opens it read-only.
    Expected<void> open(const std::filesystem::path& file, bool create, bool read_only);
    /// Closes the database (open may then be called again).
    void close();
    /// Runs SQL without results (may hold several statements).
    Expected<void> exec(std::string_view sql, std::string_view what);
    sqlite3* get() const { return db_; }
    /// Rows changed by the last INSERT/UPDATE/DELETE.
    int changes() const { return sqlite3_changes(db_); }
    const std::filesystem::path& file() const { return file_; }
    Error error(int rc, std::string_view what) const { return sqlite_error(db_, rc, file_, what); }

private:
    sqlite3* db_ = nullptr;
    std::filesystem::path file_;
};

/// A prepared statement. step() returns true while a row is available.
class Statement {
public:
    static Expected<Statement> prepare(const Connection& db, std::string_view sql);
    ~Statement();
    Statement(Statement&& other) noexcept;
    Statement& operator=(Statement&&) = delete;
    Statement(const Statement&) = delete;

    Statement& bind(int index, std::int64_t v);
    Statement& bind(int index, double v);
    Statement& bind(int index, std::string_view v);
    Statement& bind(int index, std::nullopt_t);
    /// Binds bytes as a BLOB (copied).
    Statement& bind_blob(int index, const void* data, std::size_t bytes);
    template <class T>
    Statement& bind(int index, const std::optional<T>& v) {
        return v ? bind(index, *v) : bind(index, std::nullopt);
    }

    Expected<bool> step(std::string_view what);
    /// Steps until done (INSERT/UPDATE).
    Expected<void> run(std::string_view what);

    std::int64_t int64(int col) const;
    double real(int col) const;
    std::string text(int col) const;
    bool is_null(int col) const;
    /// A BLOB column's bytes (empty for NULL).
    std::vector<unsigned char> blob(int col) const;

private:
    Statement(const Connection* db, sqlite3_stmt* stmt) : db_(db), stmt_(stmt) {}
    const Connection* db_;
    sqlite3_stmt* stmt_;
};

/// Runs `sql` (no parameters) and maps every row with `read(const Statement&)`.
template <class Read>
auto collect(const Connection& db, std::string_view sql, std::string_view what, Read read)
    -> Expected<std::vector<decltype(read(std::declval<const Statement&>()))>> {
    std::vector<decltype(read(std::declval<const Statement&>()))> rows;
    auto stmt = Statement::prepare(db, sql);
    if (!stmt) return fail(stmt.error());
    for (;;) {
        auto row = stmt->step(what);
        if (!row) return fail(row.error());
        if (!*row) return rows;
        rows.push_back(read(*stmt));
    }
}

/// `PRAGMA integrity_check`'s answer, its lines joined by "; " ("ok" when intact).
Expected<std::string> integrity_check(const Connection& db);

/// BEGIN IMMEDIATE ... COMMIT, rolled back when not committed.
class Transaction {
public:
    static Expected<Transaction> begin(Connection& db);
    ~Transaction();
    Transaction(Transaction&& other) noexcept : db_(other.db_) { other.db_ = nullptr; }
    Transaction& operator=(Transaction&&) = delete;
    Expected<void> commit();

private:
    explicit Transaction(Connection* db) : db_(db) {}
    Connection* db_;
};

}  // namespace anascan::acquisition::db
