// The commands that write outputs, on a real, size-limited file system (a tmpfs mounted by
// the test; CI runs as root): `session export --mesh` and `campaign register` with the disk
// filling in the middle. Each must fail with a message naming the file and the cause, leave
// nothing half-written under a final name, and succeed once there is space again; the
// campaign resumes to what a run on an ample disk gives. Skips where mounting is refused.
#include <sys/mount.h>

#include <cerrno>
#include <cstring>
#include <filesystem>

#include "anascan/processing/io/ply.hpp"
#include "cli_runner.hpp"
#include "kill_runner.hpp"

namespace anascan {
namespace {

namespace fs = std::filesystem;
using testing_util::run_cli;

bool contains(const std::string& text, const std::string& part) {
    return text.find(part) != std::string::npos;
}

class DiskFull : public testing_util::Cli {
protected:
    /// Mounts a tmpfs of `size` on `at`; false (with the reason) where that is refused.
    bool mount_tmpfs(const fs::path& at, const std::string& size) {
        fs::create_directories(at);
        if (::mount("tmpfs", at.c_str(), "tmpfs", 0, ("size=" + size).c_str()) != 0) {
            skip_reason_ = "cannot mount a tmpfs on " + at.string() + " (" + std::strerror(errno) +
                           "): run as root to test a full disk";
            return false;
        }
        mounts_.push_back(at);
        return true;
    }
    bool grow(const fs::path& at, const std::string& size) {
        return ::mount("tmpfs", at.c_str(), "tmpfs", MS_REMOUNT, ("size=" + size).c_str()) == 0;
    }
    void TearDown() override {
        for (auto it = mounts_.rbegin(); it != mounts_.rend(); ++it)
            ::umount2(it->c_str(), MNT_DETACH);
        Cli::TearDown();
    }
    std::vector<fs::path> mounts_;
    std::string skip_reason_;
};

TEST_F(DiskFull, SessionExportOfAMeshFailsClearlyAndWritesOnceThereIsSpace) {
    const fs::path out = dir_ / "out";
    if (!mount_tmpfs(out, "100k")) GTEST_SKIP() << skip_reason_;
    const fs::path session = dir_ / "session";
    auto run = run_cli(
        "--accept-poor capture --device sim:structured-light --scene small-block --flip-after 0 "
        "--no-coverage --views 3 --session " +
        session.string());
    ASSERT_EQ(run.exit_code, 0) << run.output;
    const std::string export_args = "--accept-poor session export " + session.string() +
                                    " --mesh " + (out / "mesh.ply").string() + " --resolution-mm 6";
    run = run_cli(export_args);
    EXPECT_EQ(run.exit_code, 1) << run.output;
    EXPECT_TRUE(contains(run.output, (out / "mesh.ply").string() + ": cannot write: No space"))
        << run.output;
    EXPECT_TRUE(fs::is_empty(out)) << "a part or a temporary was left on the full disk";
    ASSERT_TRUE(grow(out, "16m")) << std::strerror(errno);
    run = run_cli(export_args);
    ASSERT_EQ(run.exit_code, 0) << run.output;
    auto mesh = io::read_ply(out / "mesh.ply");
    ASSERT_TRUE(mesh) << mesh.error().message;
    EXPECT_GT(mesh->triangles.size(), 0u);
    EXPECT_EQ(run_cli("session check " + session.string()).exit_code, 0);
}

TEST_F(DiskFull, CampaignRegisterStopsClearlyAndResumesOnceThereIsSpace) {
    const fs::path full = dir_ / "full";
    if (!mount_tmpfs(full, "6m")) GTEST_SKIP() << skip_reason_;
    const fs::path scans = dir_ / "scans";
    auto run =
        run_cli("sim campaign --seed 3 --stones 2 --scans-per-stone 4 --out " + scans.string());
    ASSERT_EQ(run.exit_code, 0) << run.output;
    const std::string list = " --list " + (scans / "list.txt").string();
    const fs::path ample = dir_ / "ample";
    ASSERT_EQ(run_cli("campaign init " + ample.string() + list).exit_code, 0);
    ASSERT_EQ(run_cli("campaign register " + ample.string()).exit_code, 0);
    const fs::path campaign = full / "c";
    ASSERT_EQ(run_cli("campaign init " + campaign.string() + list).exit_code, 0);
    // Eight prepared clouds of about 1.2 MB each do not fit in 6 MiB.
    run = run_cli("campaign register " + campaign.string());
    EXPECT_EQ(run.exit_code, 1) << run.output;
    EXPECT_TRUE(contains(run.output, "No space left on device") ||
                contains(run.output, "disk is full"))
        << run.output;
    EXPECT_TRUE(contains(run.output, campaign.string())) << run.output;
    EXPECT_EQ(testing_util::temporaries_in(campaign), 0);
    run = run_cli("campaign check " + campaign.string());
    EXPECT_EQ(run.exit_code, 0) << run.output;
    // Space again: no scan was given up for the full disk; the job ends as on the ample disk.
    ASSERT_TRUE(grow(full, "64m")) << std::strerror(errno);
    run = run_cli("campaign register " + campaign.string());
    ASSERT_EQ(run.exit_code, 0) << run.output;
    const auto status = [](const fs::path& c) {
        return testing_util::run_cli_stdout("campaign status " + c.string()).output;
    };
    EXPECT_EQ(status(campaign), status(ample));
    EXPECT_FALSE(contains(status(campaign), "not used: ")) << status(campaign);
}

}  // namespace
}  // namespace anascan
