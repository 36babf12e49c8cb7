// The session store under faults: read-only folders, a full disk, damaged and leftover files,
// and a writer SIGKILLed at random moments.
#include <gtest/gtest.h>
#include <signal.h>
#include <sys/resource.h>
#include <sys/stat.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cstdio>
#include <fstream>
#include <set>
#include <thread>

#include "anascan/acquisition/store/session_check.hpp"
#include "anascan/acquisition/store/session_store.hpp"
#include "session_test_support.hpp"

namespace anascan::acquisition {
namespace {

namespace fs = std::filesystem;
using testing_util::make_scan;
using testing_util::SessionFolder;
using SessionFaultTest = SessionFolder;

bool contains(const std::string& text, const std::string& part) {
    return text.find(part) != std::string::npos;
}

void save_scans(const fs::path& dir, int count, std::size_t points = 30) {
    auto store = SessionStore::open(dir, SessionOpenMode::kCreateOrOpen);
    ASSERT_TRUE(store) << store.error().message;
    for (int i = 0; i < count; ++i) {
        auto saved = (*store)->save_scan(make_scan(points, static_cast<unsigned>(i)), std::nullopt);
        ASSERT_TRUE(saved) << saved.error().message;
    }
}

void expect_all_loadable(const fs::path& dir, std::size_t count) {
    auto store = SessionStore::open(dir, SessionOpenMode::kReadOnly);
    ASSERT_TRUE(store) << store.error().message;
    auto scans = (*store)->scans();
    ASSERT_TRUE(scans);
    EXPECT_EQ(scans->size(), count);
    for (const ScanRecord& r : *scans) {
        auto scan = (*store)->load_scan(r.seq);
        EXPECT_TRUE(scan) << scan.error().message;
    }
}

// Runs `body` in a forked child; its exit code is the number of failed checks, which it
// describes on stderr (gtest assertions do not cross fork).
template <class Body>
int run_in_child(Body body) {
    std::fflush(nullptr);
    const pid_t pid = ::fork();
    if (pid == 0) ::_exit(body());
    int status = 0;
    ::waitpid(pid, &status, 0);
    return WIFEXITED(status) ? WEXITSTATUS(status) : 100 + WTERMSIG(status);
}

int check(bool ok, const std::string& what) {
    if (!ok) std::fprintf(stderr, "child check failed: %s\n", what.c_str());
    return ok ? 0 : 1;
}

TEST_F(SessionFaultTest, AReadOnlyScansFolderGivesAClearErrorAndLosesNothing) {
    if (::geteuid() == 0) {
        GTEST_SKIP() << "running as root: chmod 0555 does not stop root; the read-only case is "
                        "covered by AFileWhereTheScansFolderShouldBe";
    }
    save_scans(dir_, 2);
    fs::permissions(dir_ / "scans", fs::perms(0555));
    {
        auto store = SessionStore::open(dir_, SessionOpenMode::kOpenExisting);
        ASSERT_TRUE(store) << store.error().message;
        auto saved = (*store)->save_scan(make_scan(30, 9), std::nullopt);
        ASSERT_FALSE(saved);
        EXPECT_TRUE(contains(saved.error().message, "scan_000003.ply")) << saved.error().message;
        EXPECT_TRUE(contains(saved.error().message, "not writable")) << saved.error().message;
        EXPECT_EQ((*store)->scans()->size(), 2u);
    }
    fs::permissions(dir_ / "scans", fs::perms(0755));
    expect_all_loadable(dir_, 2);
}

TEST_F(SessionFaultTest, AFileWhereTheScansFolderShouldBeGivesAClearError) {
    save_scans(dir_, 2);
    fs::rename(dir_ / "scans", root_ / "scans-aside");
    std::ofstream(dir_ / "scans") << "not a folder";
    {
        auto store = SessionStore::open(dir_, SessionOpenMode::kOpenExisting);
        ASSERT_TRUE(store) << store.error().message;
        auto saved = (*store)->save_scan(make_scan(30, 9), std::nullopt);
        ASSERT_FALSE(saved);
        EXPECT_TRUE(contains(saved.error().message, "scan_000003.ply")) << saved.error().message;
        EXPECT_TRUE(contains(saved.error().message, "Nothing was recorded"));
        EXPECT_TRUE(contains(saved.error().message, "not writable")) << saved.error().message;
        EXPECT_EQ((*store)->scans()->size(), 2u);
    }
    fs::remove(dir_ / "scans");
    fs::rename(root_ / "scans-aside", dir_ / "scans");
    expect_all_loadable(dir_, 2);
}

// RLIMIT_FSIZE stands in for a full disk (writes past the limit fail with EFBIG once
// SIGXFSZ is ignored); it is set in a child so the test process is unaffected.
TEST_F(SessionFaultTest, AFullDiskFailsTheSaveClearlyAndEarlierScansStayLoadable) {
    save_scans(dir_, 3);
    const int failures = run_in_child([&] {
        ::signal(SIGXFSZ, SIG_IGN);
        auto store = SessionStore::open(dir_, SessionOpenMode::kOpenExisting);
        if (!store) return check(false, store.error().message);
        rlimit limit{};
        ::getrlimit(RLIMIT_FSIZE, &limit);
        const rlimit original = limit;
        int failed = check(bool((*store)->add_event("test", "", "opened")), "event");
        // 1. The scan file does not fit.
        limit.rlim_cur = 256 * 1024;
        ::setrlimit(RLIMIT_FSIZE, &limit);
        auto big = (*store)->save_scan(make_scan(20000, 7), std::nullopt);
        failed += check(!big, "a 640 kB scan saved under a 256 kB limit");
        if (!big) {
            failed += check(contains(big.error().message, "scan_000004.ply"), big.error().message);
            failed += check(contains(big.error().message, "disk is full"), big.error().message);
        }
        failed += check(!fs::exists(dir_ / "scans/scan_000004.ply"), "final file left");
        // 2. The file fits but the database's WAL cannot grow: the commit fails.
        limit.rlim_cur = fs::file_size(dir_ / "session.sqlite-wal");
        ::setrlimit(RLIMIT_FSIZE, &limit);
        auto small = (*store)->save_scan(make_scan(20, 8), std::nullopt);
        failed += check(!small, "saved although the database could not grow");
        if (!small) {
            failed += check(contains(small.error().message, "scan 4"), small.error().message);
        }
        failed += check(!fs::exists(dir_ / "scans/scan_000004.ply"), "final file left (db)");
        // 3. Space again: saving continues with the next number.
        ::setrlimit(RLIMIT_FSIZE, &original);
        auto again = (*store)->save_scan(make_scan(20, 9), std::nullopt);
        failed += check(again && again->seq == 4, again ? "wrong seq" : again.error().message);
        return failed;
    });
    EXPECT_EQ(failures, 0);
    expect_all_loadable(dir_, 4);
}

TEST_F(SessionFaultTest, CheckFindsATruncatedFileAndRepairKeepsItFlagged) {
    save_scans(dir_, 3, 200);
    const fs::path damaged = dir_ / "scans/scan_000002.ply";
    fs::resize_file(damaged, fs::file_size(damaged) / 2);
    auto report = check_session(dir_);
    ASSERT_TRUE(report) << report.error().message;
    EXPECT_EQ(report->scans_checked, 3u);
    EXPECT_EQ(report->scans_ok, 2u);
    ASSERT_EQ(report->issues.size(), 1u);
    EXPECT_EQ(report->issues[0].kind, CheckIssueKind::kDamagedFile);
    EXPECT_EQ(report->issues[0].seq, std::optional<std::int64_t>(2));
    EXPECT_FALSE(report->clean());
    std::string text;
    for (const std::string& line : report->lines()) text += line + "\n";
    EXPECT_TRUE(contains(text, damaged.string())) << text;

    auto repaired = check_session(dir_, {.repair = true});
    ASSERT_TRUE(repaired);
    EXPECT_TRUE(repaired->clean());
    EXPECT_TRUE(repaired->issues.at(0).repaired);
    EXPECT_TRUE(fs::exists(damaged));  // Never deleted.
    auto store = SessionStore::open(dir_, SessionOpenMode::kReadOnly);
    ASSERT_TRUE(store);
    const ScanRecord row = *(*store)->scan(2);
    EXPECT_EQ(row.state, ScanState::kFailed);
    EXPECT_FALSE(row.file_problem.empty());
    store->reset();
    auto again = check_session(dir_);
    ASSERT_TRUE(again);
    EXPECT_TRUE(again->clean());  // Known and recorded.
    EXPECT_TRUE(again->issues.at(0).recorded);
}

TEST_F(SessionFaultTest, LeftoverFilesOfAnInterruptedSaveAreCleanedUpOrSetAside) {
    save_scans(dir_, 2);
    fs::copy_file(dir_ / "scans/scan_000001.ply", dir_ / "scans/scan_000003.ply");
    std::ofstream(dir_ / "scans/.scan_000004.ply.tmp123456") << "partial";
    auto report = check_session(dir_);
    ASSERT_TRUE(report);
    ASSERT_EQ(report->issues.size(), 2u);
    EXPECT_FALSE(report->clean());
    auto repaired = check_session(dir_, {.repair = true});
    ASSERT_TRUE(repaired);
    EXPECT_TRUE(repaired->clean());
    EXPECT_FALSE(fs::exists(dir_ / "scans/.scan_000004.ply.tmp123456"));
    EXPECT_FALSE(fs::exists(dir_ / "scans/scan_000003.ply"));
    EXPECT_TRUE(fs::exists(dir_ / "recovered/scan_000003.ply"));
    expect_all_loadable(dir_, 2);  // Not silently added.
    // Without a check, a save that finds a leftover final file sets it aside too.
    fs::copy_file(dir_ / "scans/scan_000001.ply", dir_ / "scans/scan_000003.ply");
    save_scans(dir_, 1, 7);
    EXPECT_TRUE(fs::exists(dir_ / "recovered/scan_000003.1.ply"));
    expect_all_loadable(dir_, 3);
}

// A child saves small scans in a loop and reports each acknowledged seq on a pipe; it is
// SIGKILLed a random time after its first acknowledgement. After `check --repair` every
// acknowledged scan loads.
std::set<std::int64_t> run_and_kill(const fs::path& dir, std::chrono::microseconds delay,
                                    unsigned seed) {
    int fds[2];
    EXPECT_EQ(::pipe(fds), 0);
    std::fflush(nullptr);
    const pid_t pid = ::fork();
    if (pid == 0) {
        ::close(fds[0]);
        auto store = SessionStore::open(dir, SessionOpenMode::kOpenExisting);
        if (!store) ::_exit(2);
        for (unsigned i = 0;; ++i) {
            auto saved = (*store)->save_scan(make_scan(40 + i % 50, seed + i), std::nullopt);
            if (!saved) ::_exit(3);
            if (::write(fds[1], &saved->seq, sizeof(saved->seq)) != sizeof(saved->seq)) ::_exit(4);
        }
    }
    ::close(fds[1]);
    // Wait for the first acknowledgement, so every round makes progress; the kill then lands
    // at a random moment of the following saves.
    std::set<std::int64_t> acknowledged;
    std::int64_t seq = 0;
    if (::read(fds[0], &seq, sizeof(seq)) == sizeof(seq)) acknowledged.insert(seq);
    std::this_thread::sleep_for(delay);
    ::kill(pid, SIGKILL);
    int status = 0;
    ::waitpid(pid, &status, 0);
    EXPECT_TRUE(WIFSIGNALED(status)) << "the child stopped by itself, exit " << WEXITSTATUS(status);
    while (::read(fds[0], &seq, sizeof(seq)) == sizeof(seq)) acknowledged.insert(seq);
    ::close(fds[0]);
    return acknowledged;
}

TEST_F(SessionFaultTest, EveryAcknowledgedScanSurvivesRandomKills) {
    save_scans(dir_, 1);
    std::mt19937 rng(20261122);
    std::uniform_int_distribution<int> delay_us(0, 8000);
    std::set<std::int64_t> acknowledged = {1};
    int repaired_findings = 0;
    constexpr int kKills = 60;
    for (int kill = 0; kill < kKills; ++kill) {
        const auto acked =
            run_and_kill(dir_, std::chrono::microseconds(delay_us(rng)), 1000u * kill);
        acknowledged.insert(acked.begin(), acked.end());
        if (kill % 10 == 0) {  // A read-only check right after the kill (hot WAL) works too.
            auto look = check_session(dir_);
            ASSERT_TRUE(look) << look.error().message;
            EXPECT_EQ(look->integrity, "ok");
        }
        auto report = check_session(dir_, {.repair = true});
        ASSERT_TRUE(report) << report.error().message;
        ASSERT_EQ(report->integrity, "ok");
        for (const CheckIssue& issue : report->issues) {
            ASSERT_NE(issue.kind, CheckIssueKind::kMissingFile) << issue.file;
            ASSERT_NE(issue.kind, CheckIssueKind::kDamagedFile) << issue.file;
            EXPECT_TRUE(issue.repaired) << issue.file << ": " << issue.action;
            ++repaired_findings;
        }
        auto store = SessionStore::open(dir_, SessionOpenMode::kReadOnly);
        ASSERT_TRUE(store) << store.error().message;
        auto scans = (*store)->scans();
        ASSERT_TRUE(scans);
        for (std::size_t i = 0; i < scans->size(); ++i) {
            ASSERT_EQ((*scans)[i].seq, static_cast<std::int64_t>(i + 1));  // No gaps.
        }
        for (std::int64_t seq : acknowledged) {
            auto scan = (*store)->load_scan(seq);
            ASSERT_TRUE(scan) << "kill " << kill << ": acknowledged scan " << seq
                              << " lost: " << scan.error().message;
        }
    }
    // Saving continues in the same session.
    auto store = SessionStore::open(dir_, SessionOpenMode::kOpenExisting);
    ASSERT_TRUE(store);
    const std::int64_t last = (*store)->scans()->back().seq;
    auto saved = (*store)->save_scan(make_scan(10, 5), std::nullopt);
    ASSERT_TRUE(saved) << saved.error().message;
    EXPECT_EQ(saved->seq, last + 1);
    std::printf("%d kills: %zu scans acknowledged, %lld rows, %d leftover files repaired\n", kKills,
                acknowledged.size(), static_cast<long long>(last), repaired_findings);
    EXPECT_GT(acknowledged.size(), static_cast<std::size_t>(kKills));  // >= 1 per round.
}

}  // namespace
}  // namespace anascan::acquisition
