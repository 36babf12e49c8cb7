#include "store/db.hpp"

namespace anascan::acquisition::db {
namespace {

std::string advice(int rc, const std::filesystem::path& file) {
    switch (rc & 0xff) {
        case SQLITE_FULL:
            return " (the disk is full: free space and retry; acknowledged scans are safe)";
        case SQLITE_READONLY:
        case SQLITE_PERM:
        case SQLITE_CANTOPEN:
            return " (check that the folder '" + file.parent_path().string() +
                   "' exists and is writable)";
        case SQLITE_CORRUPT:
        case SQLITE_NOTADB:
            return " (the database is damaged: run `anascan session check " +
                   file.parent_path().string() + " --repair`; the scan files are kept)";
        case SQLITE_BUSY:
        case SQLITE_LOCKED:
            return " (another program is using the session; close it and retry)";
        case SQLITE_IOERR:
            return " (input/output error: check the disk and free space)";
        default:
            return "";
    }
}

}  // namespace

Error sqlite_error(sqlite3* db, int rc, const std::filesystem::path& file, std::string_view what) {
    const char* detail = db != nullptr ? sqlite3_errmsg(db) : sqlite3_errstr(rc);
    const ErrorCode code = (rc & 0xff) == SQLITE_CORRUPT || (rc & 0xff) == SQLITE_NOTADB
                               ? ErrorCode::kFormat
                               : ((rc & 0xff) == SQLITE_BUSY ? ErrorCode::kBusy : ErrorCode::kIo);
    return Error{code, file.string() + ": " + std::string(what) + ": " + detail + advice(rc, file)};
}

Connection::~Connection() { close(); }

void Connection::close() {
    if (db_ != nullptr) sqlite3_close_v2(db_);
    db_ = nullptr;
}

Expected<void> Connection::open(const std::filesystem::path& file, bool create, bool read_only) {
    file_ = file;
    int flags = read_only ? SQLITE_OPEN_READONLY : SQLITE_OPEN_READWRITE;
    if (create && !read_only) flags |= SQLITE_OPEN_CREATE;
    const int rc = sqlite3_open_v2(file.c_str(), &db_, flags | SQLITE_OPEN_NOMUTEX, nullptr);
    if (rc != SQLITE_OK) return fail(error(rc, "cannot open the session database"));
    sqlite3_extended_result_codes(db_, 1);
    sqlite3_busy_timeout(db_, 5000);
    return {};
}

Expected<void> Connection::exec(std::string_view sql, std::string_view what) {
    const std::string text(sql);
    const int rc = sqlite3_exec(db_, text.c_str(), nullptr, nullptr, nullptr);
    if (rc != SQLITE_OK) return fail(error(rc, what));
    return {};
}

Expected<Statement> Statement::prepare(const Connection& db, std::string_view sql) {
    sqlite3_stmt* stmt = nullptr;
    const int rc =
        sqlite3_prepare_v2(db.get(), sql.data(), static_cast<int>(sql.size()), &stmt, nullptr);
    if (rc != SQLITE_OK) return fail(db.error(rc, "cannot read the session database"));
    return Statement(&db, stmt);
}

Statement::~Statement() {
    if (stmt_ != nullptr) sqlite3_finalize(stmt_);
}

Statement::Statement(Statement&& other) noexcept : db_(other.db_), stmt_(other.stmt_) {
    other.stmt_ = nullptr;
}

Statement& Statement::bind(int index, std::int64_t v) {
    sqlite3_bind_int64(stmt_, index, v);
    return *this;
}
Statement& Statement::bind(int index, double v) {
    sqlite3_bind_double(stmt_, index, v);
    return *this;
}
Statement& Statement::bind(int index, std::string_view v) {
    sqlite3_bind_text(stmt_, index, v.data(), static_cast<int>(v.size()), SQLITE_TRANSIENT);
    return *this;
}
Statement& Statement::bind(int index, std::nullopt_t) {
    sqlite3_bind_null(stmt_, index);
    return *this;
}

Statement& Statement::bind_blob(int index, const void* data, std::size_t bytes) {
    sqlite3_bind_blob64(stmt_, index, data, bytes, SQLITE_TRANSIENT);
    return *this;
}

std::vector<unsigned char> Statement::blob(int col) const {
    const auto* p = static_cast<const unsigned char*>(sqlite3_column_blob(stmt_, col));
    const int bytes = sqlite3_column_bytes(stmt_, col);
    return p == nullptr ? std::vector<unsigned char>() : std::vector<unsigned char>(p, p + bytes);
}

Expected<bool> Statement::step(std::string_view what) {
    const int rc = sqlite3_step(stmt_);
    if (rc == SQLITE_ROW) return true;
    if (rc == SQLITE_DONE) return false;
    return fail(db_->error(rc, what));
}

Expected<void> Statement::run(std::string_view what) {
    for (;;) {
        auto row = step(what);
        if (!row) return fail(row.error());
        if (!*row) return {};
    }
}

std::int64_t Statement::int64(int col) const { return sqlite3_column_int64(stmt_, col); }
double Statement::real(int col) const { return sqlite3_column_double(stmt_, col); }
bool Statement::is_null(int col) const { return sqlite3_column_type(stmt_, col) == SQLITE_NULL; }
std::string Statement::text(int col) const {
    const auto* p = reinterpret_cast<const char*>(sqlite3_column_text(stmt_, col));
    return p == nullptr ? std::string() : std::string(p, sqlite3_column_bytes(stmt_, col));
}

Expected<Transaction> Transaction::begin(Connection& db) {
    if (auto ok = db.exec("BEGIN IMMEDIATE", "cannot start a transaction"); !ok) {
        return fail(ok.error());
    }
    return Transaction(&db);
}

Transaction::~Transaction() {
    if (db_ != nullptr) sqlite3_exec(db_->get(), "ROLLBACK", nullptr, nullptr, nullptr);
}

Expected<void> Transaction::commit() {
    auto ok = db_->exec("COMMIT", "cannot commit");
    if (ok) db_ = nullptr;  // On failure the destructor rolls back.
    return ok;
}

Expected<std::string> integrity_check(const Connection& db) {
    auto lines = collect(db, "PRAGMA integrity_check", "cannot check the database",
                         [](const Statement& row) { return row.text(0); });
    if (!lines) return fail(lines.error());
    std::string result;
    for (const std::string& line : *lines) result += (result.empty() ? "" : "; ") + line;
    return result;
}

}  // namespace anascan::acquisition::db
