// SessionStore: opening (folder, lock, database, migrations) and the small tables.
#include <fcntl.h>
#include <sys/file.h>
#include <unistd.h>

#include <cerrno>
#include <cstdlib>
#include <cstring>

#include "store/codec.hpp"
#include "store/impl.hpp"
#include "store/schema.hpp"

namespace anascan::acquisition {
namespace {

namespace fs = std::filesystem;

std::int64_t now_ns() { return codec::to_ns(std::chrono::system_clock::now()); }

Expected<void> prepare_folder(const fs::path& dir, SessionOpenMode mode) {
    std::error_code ec;
    if (fs::exists(dir, ec) && !fs::is_directory(dir, ec)) {
        return fail(session_error(dir, ErrorCode::kIo, "is a file, expected a session folder"));
    }
    const bool has_db = fs::exists(dir / "session.sqlite", ec);
    if (mode != SessionOpenMode::kCreateOrOpen && !has_db) {
        return fail(session_error(dir, ErrorCode::kIo,
                                  "not a session folder (no session.sqlite): check the path"));
    }
    if (mode == SessionOpenMode::kOpenExisting && !fs::exists(dir / "scans", ec)) {
        fs::create_directories(dir / "scans", ec);  // A failure shows when saving.
    }
    if (mode != SessionOpenMode::kCreateOrOpen) return {};
    fs::create_directories(dir / "scans", ec);
    if (ec || !fs::is_directory(dir / "scans")) {
        return fail(session_error(
            dir / "scans", ErrorCode::kIo,
            "cannot create the scans folder: " + ec.message() + " (choose a writable folder)"));
    }
    return {};
}

// Exclusive lock of a writable session: two writers would allocate the same seq.
Expected<int> lock_session(const fs::path& dir) {
    const fs::path file = dir / "session.lock";
    const int fd = ::open(file.c_str(), O_RDWR | O_CREAT | O_CLOEXEC, 0644);
    if (fd < 0) {
        return fail(session_error(file, ErrorCode::kIo,
                                  std::string("cannot open: ") + std::strerror(errno) +
                                      " (the session folder must be writable)"));
    }
    if (::flock(fd, LOCK_EX | LOCK_NB) != 0) {
        ::close(fd);
        return fail(session_error(dir, ErrorCode::kBusy,
                                  "the session is open for writing by another program "
                                  "(a running capture?): close it and retry"));
    }
    return fd;
}

Expected<void> configure(db::Connection& db, bool read_only) {
    if (read_only) return db.exec("PRAGMA busy_timeout = 5000", "cannot configure");
    return db.exec("PRAGMA journal_mode = WAL; PRAGMA synchronous = FULL;",
                   "cannot switch to WAL mode");
}

Expected<void> open_database(SessionStore::Impl& impl, const fs::path& file, bool create) {
    if (auto ok = impl.db.open(file, create, impl.read_only); !ok) return fail(ok.error());
    if (auto ok = configure(impl.db, impl.read_only); !ok) return fail(ok.error());
    return db::migrate(impl.db, impl.read_only);
}

/// Copies DIR/session.sqlite and its -wal (if any) into a new private temporary folder.
Expected<fs::path> copy_database(const fs::path& dir) {
    std::string pattern = (fs::temp_directory_path() / "anascan-readonly-XXXXXX").string();
    if (::mkdtemp(pattern.data()) == nullptr)
        return fail(ErrorCode::kIo, pattern + ": cannot create a folder to read the session");
    const fs::path copy(pattern);
    std::error_code ec;
    for (const char* name : {"session.sqlite", "session.sqlite-wal"}) {
        if (!fs::exists(dir / name, ec)) continue;
        fs::copy_file(dir / name, copy / name, ec);
        if (ec) {
            fs::remove_all(copy, ec);
            return fail(ErrorCode::kIo, (dir / name).string() + ": cannot copy to read it");
        }
    }
    return copy;
}

}  // namespace

Error session_error(const fs::path& dir, ErrorCode code, std::string_view message) {
    return Error{code, dir.string() + ": " + std::string(message)};
}

Error read_only_error(const fs::path& dir) {
    return session_error(dir, ErrorCode::kInvalidArgument, "the session was opened read-only");
}

SessionStore::Impl::~Impl() {
    if (lock_fd >= 0) ::close(lock_fd);
    db.close();
    std::error_code ec;
    if (!database_copy_dir.empty()) fs::remove_all(database_copy_dir, ec);
}

SessionStore::SessionStore(std::unique_ptr<Impl> impl) : impl_(std::move(impl)) {}
SessionStore::~SessionStore() = default;

Expected<std::unique_ptr<SessionStore>> SessionStore::open(const fs::path& dir,
                                                           SessionOpenMode mode) {
    if (auto ok = prepare_folder(dir, mode); !ok) return fail(ok.error());
    auto impl = std::make_unique<Impl>();
    impl->dir = dir;
    impl->read_only = mode == SessionOpenMode::kReadOnly;
    if (!impl->read_only && mode != SessionOpenMode::kEdit) {
        auto fd = lock_session(dir);
        if (!fd) return fail(fd.error());
        impl->lock_fd = *fd;
    }
    const bool create = mode == SessionOpenMode::kCreateOrOpen;
    auto opened = open_database(*impl, dir / "session.sqlite", create);
    if (!opened && impl->read_only) {
        // A read-only folder (archive, CD, network copy) whose write-ahead log SQLite cannot
        // use in place: read a private copy of the database and its log instead.
        impl->db.close();
        auto copy = copy_database(dir);
        if (!copy) return fail(opened.error());
        impl->database_copy_dir = *copy;
        opened = open_database(*impl, *copy / "session.sqlite", false);
    }
    if (!opened) return fail(opened.error());
    return std::unique_ptr<SessionStore>(new SessionStore(std::move(impl)));
}

const fs::path& SessionStore::dir() const { return impl_->dir; }
bool SessionStore::read_only() const { return impl_->read_only; }

Expected<void> SessionStore::add_event(std::string_view kind, std::string_view device,
                                       std::string_view message) {
    if (impl_->read_only) return fail(read_only_error(impl_->dir));
    std::lock_guard lock(impl_->mutex);
    auto stmt = db::Statement::prepare(
        impl_->db, "INSERT INTO events(time_ns, kind, device, message) VALUES(?,?,?,?)");
    if (!stmt) return fail(stmt.error());
    stmt->bind(1, now_ns()).bind(2, kind).bind(3, device).bind(4, message);
    return stmt->run("cannot record an event");
}

Expected<void> SessionStore::add_note(std::optional<std::int64_t> seq, std::string_view text) {
    if (impl_->read_only) return fail(read_only_error(impl_->dir));
    std::lock_guard lock(impl_->mutex);
    if (seq) {
        auto check = db::Statement::prepare(impl_->db, "SELECT 1 FROM scans WHERE seq = ?");
        if (!check) return fail(check.error());
        check->bind(1, *seq);
        auto row = check->step("cannot read the scan list");
        if (!row) return fail(row.error());
        if (!*row) {
            return fail(session_error(impl_->dir, ErrorCode::kInvalidArgument,
                                      "no scan " + std::to_string(*seq) + " in this session"));
        }
    }
    auto stmt =
        db::Statement::prepare(impl_->db, "INSERT INTO notes(time_ns, seq, text) VALUES(?,?,?)");
    if (!stmt) return fail(stmt.error());
    stmt->bind(1, now_ns()).bind(2, seq).bind(3, text);
    return stmt->run("cannot record a note");
}

Expected<std::vector<EventRecord>> SessionStore::events() const {
    std::lock_guard lock(impl_->mutex);
    return db::collect(impl_->db,
                       "SELECT id, time_ns, kind, device, message FROM events ORDER BY id",
                       "cannot read the events", [](const db::Statement& row) {
                           return EventRecord{row.int64(0), codec::from_ns(row.int64(1)),
                                              row.text(2), row.text(3), row.text(4)};
                       });
}

Expected<std::vector<SessionNote>> SessionStore::notes() const {
    std::lock_guard lock(impl_->mutex);
    return db::collect(
        impl_->db, "SELECT id, time_ns, seq, text FROM notes ORDER BY id", "cannot read the notes",
        [](const db::Statement& row) {
            SessionNote note{row.int64(0), codec::from_ns(row.int64(1)), std::nullopt, row.text(3)};
            if (!row.is_null(2)) note.seq = row.int64(2);
            return note;
        });
}

Expected<std::vector<DeviceRecord>> SessionStore::devices() const {
    std::lock_guard lock(impl_->mutex);
    return db::collect(
        impl_->db, "SELECT id, kind, first_seen_ns FROM devices ORDER BY first_seen_ns, id",
        "cannot read the devices", [](const db::Statement& row) {
            return DeviceRecord{row.text(0), codec::device_kind_from_string(row.text(1)),
                                codec::from_ns(row.int64(2))};
        });
}

Expected<std::string> SessionStore::integrity_check() const {
    std::lock_guard lock(impl_->mutex);
    return db::integrity_check(impl_->db);
}

Expected<void> SessionStore::set_value(std::string_view key, std::string_view json) {
    if (impl_->read_only) return fail(read_only_error(impl_->dir));
    std::lock_guard lock(impl_->mutex);
    auto stmt = db::Statement::prepare(
        impl_->db, "INSERT OR REPLACE INTO session_values(key, json) VALUES(?,?)");
    if (!stmt) return fail(stmt.error());
    stmt->bind(1, key).bind(2, json);
    return stmt->run("cannot store the value '" + std::string(key) + "'");
}

Expected<std::optional<std::string>> SessionStore::value(std::string_view key) const {
    std::lock_guard lock(impl_->mutex);
    auto stmt = db::Statement::prepare(impl_->db, "SELECT json FROM session_values WHERE key = ?");
    if (!stmt) return fail(stmt.error());
    stmt->bind(1, key);
    auto row = stmt->step("cannot read the value '" + std::string(key) + "'");
    if (!row) return fail(row.error());
    if (!*row) return std::optional<std::string>();
    return std::optional<std::string>(stmt->text(0));
}

Expected<void> SessionStore::checkpoint() {
    if (impl_->read_only) return fail(read_only_error(impl_->dir));
    std::lock_guard lock(impl_->mutex);
    return impl_->db.exec("PRAGMA wal_checkpoint(TRUNCATE)", "cannot fold the WAL in");
}

}  // namespace anascan::acquisition
