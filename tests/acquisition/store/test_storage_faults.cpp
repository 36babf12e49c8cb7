// The session store on a real, size-limited file system (tmpfs mounted by the test; CI runs
// as root): the disk filling in the middle of a scan, the scans folder turning read-only,
// the -wal file deleted or truncated after a kill, a torn write and flipped bits in a scan
// file. Skips with a message where mounting is not permitted.
#include <gtest/gtest.h>
#include <signal.h>
#include <sqlite3.h>
#include <sys/mount.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>
#include <fstream>
#include <set>

#include "anascan/acquisition/store/session_check.hpp"
#include "anascan/acquisition/store/session_store.hpp"
#include "session_test_support.hpp"

namespace anascan::acquisition {
namespace {

namespace fs = std::filesystem;
using testing_util::make_scan;

bool contains(const std::string& text, const std::string& part) {
    return text.find(part) != std::string::npos;
}

// A scratch folder with a tmpfs of `size` mounted on it (unmounted afterwards).
class TmpfsSession : public testing_util::SessionFolder {
protected:
    bool mount_tmpfs(const fs::path& at, const std::string& size) {
        fs::create_directories(at);
        const std::string options = "size=" + size;
        if (::mount("tmpfs", at.c_str(), "tmpfs", 0, options.c_str()) != 0) {
            skip_reason_ = "cannot mount a tmpfs on " + at.string() + " (" + std::strerror(errno) +
                           "): run as root to test real storage faults";
            return false;
        }
        mounts_.push_back(at);
        return true;
    }
    bool remount(const fs::path& at, unsigned long flags, const std::string& options) {
        return ::mount("tmpfs", at.c_str(), "tmpfs", MS_REMOUNT | flags, options.c_str()) == 0;
    }
    void TearDown() override {
        for (auto it = mounts_.rbegin(); it != mounts_.rend(); ++it)
            ::umount2(it->c_str(), MNT_DETACH);
        SessionFolder::TearDown();
    }
    std::vector<fs::path> mounts_;
    std::string skip_reason_;
};

std::vector<std::string> files_in(const fs::path& folder) {
    std::vector<std::string> names;
    std::error_code ec;
    for (const auto& e : fs::directory_iterator(folder, ec)) names.push_back(e.path().filename());
    return names;
}

// Every acknowledged seq has a row whose file loads (CRC-32 and point count checked).
void expect_loadable(const fs::path& dir, const std::set<std::int64_t>& acknowledged) {
    auto store = SessionStore::open(dir, SessionOpenMode::kReadOnly);
    ASSERT_TRUE(store) << store.error().message;
    for (std::int64_t seq : acknowledged) {
        auto scan = (*store)->load_scan(seq);
        EXPECT_TRUE(scan) << "acknowledged scan " << seq << " lost: " << scan.error().message;
    }
}

TEST_F(TmpfsSession, TheDiskFillingMidScanFailsThatScanClearlyAndKeepsTheOthers) {
    if (!mount_tmpfs(root_, "320k")) GTEST_SKIP() << skip_reason_;
    std::set<std::int64_t> acknowledged;
    {
        auto store = SessionStore::open(dir_, SessionOpenMode::kCreateOrOpen);
        ASSERT_TRUE(store) << store.error().message;
        std::string error;
        for (unsigned i = 0; i < 200 && error.empty(); ++i) {
            auto saved = (*store)->save_scan(make_scan(700, i), std::nullopt);
            if (saved)
                acknowledged.insert(saved->seq);
            else
                error = saved.error().message;
        }
        ASSERT_FALSE(error.empty()) << "320 KiB never filled up";
        EXPECT_TRUE(contains(error, "disk is full")) << error;
        EXPECT_TRUE(contains(error, dir_.string())) << error;
        for (const std::string& name : files_in(dir_ / "scans")) {
            EXPECT_FALSE(contains(name, ".tmp")) << "temporary file left: " << name;
        }
        EXPECT_EQ(files_in(dir_ / "scans").size(), acknowledged.size());
        // Space again (the operator freed some): the session goes on with the next number.
        ASSERT_TRUE(remount(root_, 0, "size=4m"));
        auto again = (*store)->save_scan(make_scan(700, 999), std::nullopt);
        ASSERT_TRUE(again) << again.error().message;
        EXPECT_EQ(again->seq, static_cast<std::int64_t>(acknowledged.size()) + 1);
        acknowledged.insert(again->seq);
    }
    EXPECT_GE(acknowledged.size(), 3u);
    expect_loadable(dir_, acknowledged);
    auto report = check_session(dir_);
    ASSERT_TRUE(report) << report.error().message;
    EXPECT_TRUE(report->clean()) << report->lines().back();
    EXPECT_EQ(report->scans_ok, acknowledged.size());
}

TEST_F(TmpfsSession, TheScansFolderTurningReadOnlyFailsTheSaveClearlyAndRecovers) {
    // The scans folder is its own file system: remounting read-only is refused while a file
    // on it is open for writing, and the database stays open for the whole session.
    if (!mount_tmpfs(dir_ / "scans", "4m")) GTEST_SKIP() << skip_reason_;
    auto store = SessionStore::open(dir_, SessionOpenMode::kCreateOrOpen);
    ASSERT_TRUE(store) << store.error().message;
    std::set<std::int64_t> acknowledged;
    for (unsigned i = 0; i < 3; ++i)
        acknowledged.insert((*store)->save_scan(make_scan(300, i), std::nullopt)->seq);
    ASSERT_TRUE(remount(dir_ / "scans", MS_RDONLY, "")) << std::strerror(errno);
    auto refused = (*store)->save_scan(make_scan(300, 7), std::nullopt);
    ASSERT_FALSE(refused);
    EXPECT_TRUE(contains(refused.error().message, "not writable")) << refused.error().message;
    EXPECT_TRUE(contains(refused.error().message, "scan 4")) << refused.error().message;
    ASSERT_TRUE(remount(dir_ / "scans", 0, ""));
    auto again = (*store)->save_scan(make_scan(300, 8), std::nullopt);
    ASSERT_TRUE(again) << again.error().message;
    EXPECT_EQ(again->seq, 4);
    acknowledged.insert(again->seq);
    store->reset();
    expect_loadable(dir_, acknowledged);
    auto report = check_session(dir_);
    ASSERT_TRUE(report);
    EXPECT_TRUE(report->clean()) << report->lines().back();
}

// A child saves scans and reports each acknowledged seq on a pipe until it is SIGKILLed
// after `count` acknowledgements: the database is left with its -wal file, not checkpointed.
std::set<std::int64_t> save_then_kill(const fs::path& dir, int count) {
    int fds[2];
    EXPECT_EQ(::pipe(fds), 0);
    std::fflush(nullptr);
    const pid_t pid = ::fork();
    if (pid == 0) {
        ::close(fds[0]);
        auto store = SessionStore::open(dir, SessionOpenMode::kCreateOrOpen);
        if (!store) ::_exit(2);
        for (int i = 0; i < count; ++i) {
            auto saved =
                (*store)->save_scan(make_scan(200, static_cast<unsigned>(i)), std::nullopt);
            if (!saved || ::write(fds[1], &saved->seq, sizeof(saved->seq)) != sizeof(saved->seq))
                ::_exit(3);
        }
        ::pause();
    }
    ::close(fds[1]);
    std::set<std::int64_t> acknowledged;
    std::int64_t seq = 0;
    while (static_cast<int>(acknowledged.size()) < count &&
           ::read(fds[0], &seq, sizeof(seq)) == sizeof(seq)) {
        acknowledged.insert(seq);
    }
    ::kill(pid, SIGKILL);
    ::waitpid(pid, nullptr, 0);
    ::close(fds[0]);
    return acknowledged;
}

TEST_F(TmpfsSession, ADeletedOrTruncatedWalIsNamedAndNoScanFileIsDeleted) {
    if (!mount_tmpfs(root_, "8m")) GTEST_SKIP() << skip_reason_;
    for (const bool truncate : {false, true}) {
        const fs::path dir = root_ / (truncate ? "truncated" : "deleted");
        const std::set<std::int64_t> acknowledged = save_then_kill(dir, 6);
        ASSERT_EQ(acknowledged.size(), 6u);
        const fs::path wal = dir / "session.sqlite-wal";
        ASSERT_TRUE(fs::exists(wal)) << "the kill left no -wal file";
        if (truncate)
            fs::resize_file(wal, fs::file_size(wal) / 2);
        else
            fs::remove(wal);
        auto report = check_session(dir, {.repair = true});
        ASSERT_TRUE(report) << report.error().message;
        std::string text;
        for (const std::string& line : report->lines()) text += line + "\n";
        // Rows committed only to the lost part of the WAL are gone; their files are not:
        // each is named and set aside in recovered/, never deleted.
        std::size_t kept = report->scans_ok;
        for (const CheckIssue& issue : report->issues) {
            EXPECT_EQ(issue.kind, CheckIssueKind::kUnacknowledgedFile) << text;
            EXPECT_TRUE(contains(text, issue.file.filename().string())) << text;
            ++kept;
        }
        EXPECT_EQ(kept, acknowledged.size()) << text;
        EXPECT_EQ(files_in(dir / "scans").size() + files_in(dir / "recovered").size(), 6u);
        EXPECT_TRUE(report->clean()) << text;
    }
}

// Flips one bit in the middle of a scan file's point data: it still parses with the right
// point count, so only the CRC-32 recorded at acknowledgement finds it.
void flip_bit(const fs::path& file, std::uintmax_t at) {
    std::fstream f(file, std::ios::in | std::ios::out | std::ios::binary);
    f.seekg(static_cast<std::streamoff>(at));
    char c = 0;
    f.read(&c, 1);
    c = static_cast<char>(c ^ 0x10);
    f.seekp(static_cast<std::streamoff>(at));
    f.write(&c, 1);
}

TEST_F(TmpfsSession, CheckNamesEveryScanWithFlippedBitsOrATornWrite) {
    if (!mount_tmpfs(root_, "8m")) GTEST_SKIP() << skip_reason_;
    {
        auto store = SessionStore::open(dir_, SessionOpenMode::kCreateOrOpen);
        ASSERT_TRUE(store);
        for (unsigned i = 0; i < 6; ++i)
            ASSERT_TRUE((*store)->save_scan(make_scan(250, i), std::nullopt));
    }
    const fs::path flipped = dir_ / "scans/scan_000002.ply";
    const fs::path flipped_twice = dir_ / "scans/scan_000005.ply";
    const fs::path torn = dir_ / "scans/scan_000004.ply";
    flip_bit(flipped, fs::file_size(flipped) - 1000);
    flip_bit(flipped_twice, fs::file_size(flipped_twice) / 2);
    flip_bit(flipped_twice, fs::file_size(flipped_twice) - 3);
    // A torn write: the second half of the file replaced by what an earlier write left.
    const std::uintmax_t size = fs::file_size(torn);
    {
        std::fstream f(torn, std::ios::in | std::ios::out | std::ios::binary);
        f.seekp(static_cast<std::streamoff>(size / 2));
        f << std::string(size - size / 2, '\0');
    }
    auto report = check_session(dir_);
    ASSERT_TRUE(report);
    std::set<std::int64_t> named;
    for (const CheckIssue& issue : report->issues) {
        EXPECT_EQ(issue.kind, CheckIssueKind::kDamagedFile);
        EXPECT_TRUE(contains(issue.problem, "CRC-32")) << issue.problem;
        named.insert(issue.seq.value_or(0));
    }
    EXPECT_EQ(named, (std::set<std::int64_t>{2, 4, 5}));
    auto store = SessionStore::open(dir_, SessionOpenMode::kReadOnly);
    auto load = (*store)->load_scan(2);
    ASSERT_FALSE(load);
    EXPECT_TRUE(contains(load.error().message, flipped.string())) << load.error().message;
    store->reset();
    auto repaired = check_session(dir_, {.repair = true});
    ASSERT_TRUE(repaired);
    EXPECT_TRUE(repaired->clean());
    expect_loadable(dir_, {1, 3, 6});  // Every intact acknowledged scan kept.
    EXPECT_TRUE(fs::exists(flipped) && fs::exists(torn) && fs::exists(flipped_twice));
}

TEST_F(TmpfsSession, ScansSavedWithoutAChecksumGetOneFromRepair) {
    {
        auto store = SessionStore::open(dir_, SessionOpenMode::kCreateOrOpen);
        ASSERT_TRUE(store);
        for (unsigned i = 0; i < 3; ++i)
            ASSERT_TRUE((*store)->save_scan(make_scan(50, i), std::nullopt));
    }
    sqlite3* db = nullptr;  // As an anascan before schema 3 left them.
    ASSERT_EQ(sqlite3_open((dir_ / "session.sqlite").c_str(), &db), SQLITE_OK);
    ASSERT_EQ(sqlite3_exec(db, "UPDATE scans SET file_crc32 = NULL", nullptr, nullptr, nullptr),
              SQLITE_OK);
    sqlite3_close(db);
    auto report = check_session(dir_);
    ASSERT_TRUE(report);
    EXPECT_TRUE(report->clean());
    EXPECT_EQ(report->scans_without_checksum, 3u);
    auto repaired = check_session(dir_, {.repair = true});
    ASSERT_TRUE(repaired);
    EXPECT_EQ(repaired->checksums_recorded, 3u);
    auto again = check_session(dir_);
    ASSERT_TRUE(again);
    EXPECT_EQ(again->scans_without_checksum, 0u);
    auto store = SessionStore::open(dir_, SessionOpenMode::kReadOnly);
    EXPECT_TRUE((*store)->scan(2)->file_crc32.has_value());
}

}  // namespace
}  // namespace anascan::acquisition
