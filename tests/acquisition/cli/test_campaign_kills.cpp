// `anascan campaign register` SIGKILLed at random moments of its run: after each kill
// `campaign check` finds the store intact, no prepared cloud is half-written under its final
// name, and the job resumed to its end reports what an unkilled run reported.
// ANASCAN_WRITE_KILLS sets the kills (5 here; scripts/write-kill-soak.sh asks for more).
#include <cstdio>
#include <filesystem>

#include "anascan/processing/io/ply.hpp"
#include "cli_runner.hpp"
#include "kill_runner.hpp"

namespace anascan {
namespace {

namespace fs = std::filesystem;
using testing_util::run_cli;
using testing_util::run_to_end;

class CampaignKills : public testing_util::Cli {
protected:
    // Twelve simulated scans of two stones and a campaign made of them, once for the suite.
    static void SetUpTestSuite() {
        source_ = fs::path(::testing::TempDir()) / ("campaign-kills-" + std::to_string(::getpid()));
        fs::remove_all(source_);
        auto run = run_cli("sim campaign --seed 3 --stones 2 --scans-per-stone 6 --out " +
                           (source_ / "scans").string());
        ASSERT_EQ(run.exit_code, 0) << run.output;
        run = run_cli("campaign init " + (source_ / "c").string() + " --list " +
                      (source_ / "scans" / "list.txt").string());
        ASSERT_EQ(run.exit_code, 0) << run.output;
    }
    static void TearDownTestSuite() { fs::remove_all(source_); }

    /// A fresh copy of the initialised campaign (its scans stay in the suite's folder).
    fs::path copy_of_campaign(const std::string& name) {
        const fs::path to = dir_ / name;
        fs::copy(source_ / "c", to, fs::copy_options::recursive);
        return to;
    }
    static std::string status(const fs::path& campaign) {
        return testing_util::run_cli_stdout("campaign status " + campaign.string()).output;
    }

    static inline fs::path source_;
};

/// Every prepared cloud under its final name reads completely.
void expect_prepared_complete(const fs::path& campaign, int kill) {
    for (const auto& entry : fs::directory_iterator(campaign / "prepared")) {
        if (entry.path().filename().string().starts_with('.')) continue;
        auto ply = io::read_ply(entry.path());
        EXPECT_TRUE(ply) << "kill " << kill << ": half-written " << ply.error().message;
    }
}

TEST_F(CampaignKills, RegisterKilledLeavesAnIntactStoreAndResumesToTheSameResult) {
    const fs::path unkilled = copy_of_campaign("unkilled");
    const auto run_time = run_to_end("campaign register " + unkilled.string());
    const std::string expected = status(unkilled);
    ASSERT_NE(expected.find("stones: "), std::string::npos) << expected;
    int while_running = 0, temporaries = 0;
    const auto moments = testing_util::kill_moments(run_time);
    for (std::size_t k = 0; k < moments.size(); ++k) {
        // Each kill hits a fresh job, so the moments cover every stage of the run.
        const fs::path campaign = copy_of_campaign("c" + std::to_string(k));
        const auto run = testing_util::run_and_kill({"campaign", "register", campaign.string()},
                                                    moments[k], false);
        if (!run.exited_before_kill) ++while_running;
        const int kill = static_cast<int>(k);
        const auto check = run_cli("campaign check " + campaign.string());
        ASSERT_EQ(check.exit_code, 0) << "kill " << kill << ":\n" << check.output;
        expect_prepared_complete(campaign, kill);
        temporaries += testing_util::temporaries_in(campaign);
        run_to_end("campaign register " + campaign.string());
        EXPECT_EQ(status(campaign), expected) << "kill " << kill << ": the resumed job differs";
        if (HasFailure()) return;
        fs::remove_all(campaign);
    }
    std::printf(
        "campaign register: %zu kills (%d while running, run %lld ms), 0 half-written "
        "prepared clouds, %d temporaries left, every resumed job as the unkilled one\n",
        moments.size(), while_running, static_cast<long long>(run_time.count()), temporaries);
    EXPECT_GT(while_running, 0);
}

}  // namespace
}  // namespace anascan
