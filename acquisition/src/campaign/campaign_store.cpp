// CampaignStore: the folder, its lock, the database and its schema.
#include "anascan/acquisition/campaign/campaign_store.hpp"

#include <fcntl.h>
#include <sys/file.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>

#include "campaign/store_impl.hpp"
#include "store/schema.hpp"

namespace anascan::acquisition {
namespace {

namespace fs = std::filesystem;

// Version 1: the first schema. Never edit a shipped migration; add a new one.
constexpr std::string_view kV1 = R"sql(
CREATE TABLE campaign_values(key TEXT PRIMARY KEY, json TEXT NOT NULL);
CREATE TABLE scans(
    id INTEGER PRIMARY KEY,
    file TEXT NOT NULL UNIQUE,
    state TEXT NOT NULL DEFAULT 'new',
    problem TEXT NOT NULL DEFAULT '',
    summary_json TEXT NOT NULL DEFAULT '',
    keys BLOB);
CREATE TABLE pairs(
    source INTEGER NOT NULL,
    target INTEGER NOT NULL,
    similarity REAL NOT NULL,
    result_json TEXT NOT NULL DEFAULT '',
    PRIMARY KEY(source, target));
CREATE TABLE stones(id INTEGER PRIMARY KEY, scans_json TEXT NOT NULL,
                    result_json TEXT NOT NULL DEFAULT '');
)sql";

Error campaign_error(const fs::path& dir, ErrorCode code, const std::string& message) {
    return Error{code, dir.string() + ": " + message};
}

Expected<int> lock_campaign(const fs::path& dir) {
    const fs::path file = dir / "campaign.lock";
    const int fd = ::open(file.c_str(), O_RDWR | O_CREAT | O_CLOEXEC, 0644);
    if (fd < 0) {
        return fail(campaign_error(file, ErrorCode::kIo,
                                   std::string("cannot open: ") + std::strerror(errno) +
                                       " (the campaign folder must be writable)"));
    }
    if (::flock(fd, LOCK_EX | LOCK_NB) != 0) {
        ::close(fd);
        return fail(campaign_error(dir, ErrorCode::kBusy,
                                   "the campaign is in use by another job (a running `anascan "
                                   "campaign register`?): wait for it to end or stop it, then "
                                   "retry"));
    }
    return fd;
}

Expected<void> check_schema(const db::Connection& db, const fs::path& dir) {
    auto version = db::schema_version(db);
    if (!version) return fail(version.error());
    if (*version > kCampaignSchemaVersion) {
        return fail(campaign_error(dir, ErrorCode::kUnsupported,
                                   "the campaign was written by a newer anascan (schema " +
                                       std::to_string(*version) + ", this program knows up to " +
                                       std::to_string(kCampaignSchemaVersion) +
                                       "): update anascan to continue it; nothing was changed"));
    }
    if (*version < 1) {
        return fail(campaign_error(dir, ErrorCode::kFormat,
                                   "campaign.sqlite has no campaign schema (not a campaign "
                                   "folder made by `anascan campaign init`?)"));
    }
    return {};
}

Expected<std::unique_ptr<CampaignStore::Impl>> open_impl(const fs::path& dir, bool create,
                                                         bool read_only) {
    auto impl = std::make_unique<CampaignStore::Impl>();
    impl->dir = dir;
    if (!read_only) {
        auto fd = lock_campaign(dir);
        if (!fd) return fail(fd.error());
        impl->lock_fd = *fd;
    }
    if (auto ok = impl->db.open(dir / "campaign.sqlite", create, read_only); !ok) {
        return fail(ok.error());
    }
    const char* pragmas = read_only ? "PRAGMA busy_timeout = 5000"
                                    : "PRAGMA journal_mode = WAL; PRAGMA synchronous = FULL;";
    if (auto ok = impl->db.exec(pragmas, "cannot configure the campaign database"); !ok) {
        return fail(ok.error());
    }
    return impl;
}

Expected<void> write_schema(db::Connection& db, const std::vector<std::string>& files) {
    auto tx = db::Transaction::begin(db);
    if (!tx) return fail(tx.error());
    if (auto ok = db.exec(kV1, "cannot create the campaign schema"); !ok) return ok;
    for (std::size_t i = 0; i < files.size(); ++i) {
        auto stmt = db::Statement::prepare(db, "INSERT INTO scans(id, file) VALUES(?, ?)");
        if (!stmt) return fail(stmt.error());
        stmt->bind(1, static_cast<std::int64_t>(i)).bind(2, std::string_view(files[i]));
        if (auto ok = stmt->run("cannot record the scan " + files[i]); !ok) return ok;
    }
    const std::string version = "PRAGMA user_version = " + std::to_string(kCampaignSchemaVersion);
    if (auto ok = db.exec(version, "cannot set the schema version"); !ok) return ok;
    return tx->commit();
}

}  // namespace

CampaignStore::Impl::~Impl() {
    db.close();
    if (lock_fd >= 0) ::close(lock_fd);
}

CampaignStore::CampaignStore(std::unique_ptr<Impl> impl) : impl_(std::move(impl)) {}
CampaignStore::~CampaignStore() = default;

Expected<std::unique_ptr<CampaignStore>> CampaignStore::create(
    const fs::path& dir, const std::vector<std::string>& files) {
    std::error_code ec;
    if (fs::exists(dir / "campaign.sqlite", ec)) {
        return fail(campaign_error(dir, ErrorCode::kInvalidArgument,
                                   "already a campaign folder: use `anascan campaign register` "
                                   "to continue it, or choose a new folder"));
    }
    fs::create_directories(dir / "prepared", ec);
    if (ec) {
        return fail(campaign_error(dir, ErrorCode::kIo,
                                   "cannot create the campaign folder: " + ec.message()));
    }
    auto impl = open_impl(dir, true, false);
    if (!impl) return fail(impl.error());
    if (auto ok = write_schema((*impl)->db, files); !ok) return fail(ok.error());
    return std::unique_ptr<CampaignStore>(new CampaignStore(std::move(*impl)));
}

Expected<std::unique_ptr<CampaignStore>> CampaignStore::open(const fs::path& dir, bool read_only) {
    std::error_code ec;
    if (!fs::exists(dir / "campaign.sqlite", ec)) {
        return fail(campaign_error(dir, ErrorCode::kIo,
                                   "not a campaign folder (no campaign.sqlite): create it with "
                                   "`anascan campaign init DIR SCAN...`"));
    }
    auto impl = open_impl(dir, false, read_only);
    if (!impl) return fail(impl.error());
    if (auto ok = check_schema((*impl)->db, dir); !ok) return fail(ok.error());
    fs::create_directories(dir / "prepared", ec);
    return std::unique_ptr<CampaignStore>(new CampaignStore(std::move(*impl)));
}

const fs::path& CampaignStore::dir() const { return impl_->dir; }

fs::path CampaignStore::prepared_file(std::int64_t id) const {
    return impl_->dir / "prepared" / ("scan_" + std::to_string(id) + ".ply");
}

}  // namespace anascan::acquisition
