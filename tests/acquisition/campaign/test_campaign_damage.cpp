// A campaign folder damaged after the fact (a bit flip, another tool's edit): every reader
// names what is damaged instead of crashing or indexing out of range, the job stops before
// any task, `campaign check` finds exactly what the readers trip on, and `--repair` sets back
// only that work, so the next run redoes it.
#include <gmock/gmock.h>
#include <gtest/gtest.h>
#include <sqlite3.h>

#include <filesystem>
#include <string>
#include <vector>

#include "anascan/acquisition/campaign/campaign_check.hpp"
#include "anascan/acquisition/campaign/campaign_job.hpp"
#include "anascan/acquisition/campaign/campaign_results.hpp"
#include "campaign_template.hpp"

namespace anascan::acquisition {
namespace {

namespace fs = std::filesystem;
using ::testing::HasSubstr;

/// Records the tasks it is given and runs none.
class RecordingExecutor : public CampaignExecutor {
public:
    Expected<void> run(std::vector<CampaignTask> tasks, const Sink&) override {
        for (const CampaignTask& t : tasks) given.push_back(t);
        return {};
    }
    int ranks() const override { return 1; }
    std::vector<CampaignTask> given;
};

class CampaignDamage : public ::testing::Test {
protected:
    void SetUp() override {
        dir_ = fs::temp_directory_path() /
               ("anascan_campaign_damage_" +
                std::string(::testing::UnitTest::GetInstance()->current_test_info()->name()));
        fs::remove_all(dir_);
        test::write_campaign_template(dir_);
    }
    void TearDown() override { fs::remove_all(dir_); }

    std::unique_ptr<CampaignStore> open() {
        auto store = CampaignStore::open(dir_, false);
        EXPECT_TRUE(store) << store.error().message;
        return std::move(*store);
    }
    void sql(const std::string& statement) {
        sqlite3* db = nullptr;
        ASSERT_EQ(sqlite3_open((dir_ / "campaign.sqlite").c_str(), &db), SQLITE_OK);
        EXPECT_EQ(sqlite3_exec(db, statement.c_str(), nullptr, nullptr, nullptr), SQLITE_OK);
        sqlite3_close(db);
    }
    Expected<CampaignStatus> status() {
        auto store = CampaignStore::open(dir_, true);
        if (!store) return fail(store.error());
        return campaign_status(**store);
    }
    /// The job on the store with an executor that runs nothing: its error, or the tasks.
    Expected<std::vector<CampaignTask>> job() {
        RecordingExecutor executor;
        auto ran = run_campaign(*open(), executor, CampaignConfig{}, {});
        if (!ran) return fail(ran.error());
        return executor.given;
    }
    CampaignCheckReport check(bool repair) {
        auto report = check_campaign(dir_, repair);
        EXPECT_TRUE(report) << report.error().message;
        return *report;
    }
    fs::path dir_;
};

TEST_F(CampaignDamage, TheIntactCampaignReadsAndItsStatusCountsEveryStage) {
    const auto s = status();
    ASSERT_TRUE(s) << s.error().message;
    EXPECT_EQ(s->scans, 5u);
    EXPECT_EQ(s->described, 4u);
    EXPECT_EQ(s->unusable, 1u);
    EXPECT_EQ(s->registered, 4u);
    EXPECT_EQ(s->verified, 3u);
    EXPECT_EQ(s->stones, 2u);
    EXPECT_EQ(s->stones_done, 1u);
    EXPECT_EQ(s->placed, 2u);
    EXPECT_EQ(s->problems, (std::vector<std::string>{
                               "not used: /nonexistent/scan_4.ply: unreadable scan: gone",
                               "warning (stone 0): /nonexistent/scan_1.ply: match graph: a doubt",
                               "not placed (stone 0): /nonexistent/scan_2.ply: no verified link"}));
    EXPECT_TRUE(check(false).clean());
    const auto tasks = job();
    ASSERT_TRUE(tasks) << tasks.error().message;
    ASSERT_EQ(tasks->size(), 1u);  // Stone 1 has no multi-view result yet.
    EXPECT_EQ((*tasks)[0].kind, CampaignTaskKind::kStone);
}

TEST_F(CampaignDamage, AResultOfTheWrongTypeIsNamedAndRepairedSoThatOnlyThatPairIsRedone) {
    ASSERT_TRUE(open()->save_pair_result(2, 1, R"({"verified":"yes"})"));
    for (const Error& e : {status().error(), job().error()}) {
        EXPECT_EQ(e.code, ErrorCode::kFormat);
        EXPECT_THAT(e.message,
                    HasSubstr("campaign.sqlite: pair 2-1: the pair's result is damaged"));
        EXPECT_THAT(e.message, HasSubstr("anascan campaign check " + dir_.string() + " --repair"));
    }
    const CampaignCheckReport found = check(false);
    ASSERT_EQ(found.unresolved(), 1u);
    EXPECT_EQ(found.issues[0].kind, "pair-result");
    EXPECT_TRUE(check(true).clean());
    const auto tasks = job();
    ASSERT_TRUE(tasks) << tasks.error().message;
    ASSERT_EQ(tasks->size(), 2u);
    EXPECT_EQ((*tasks)[0].kind, CampaignTaskKind::kPair);
    EXPECT_THAT((*tasks)[0].input_json, HasSubstr("scan_2.ply"));
    EXPECT_THAT((*tasks)[0].input_json, HasSubstr("scan_1.ply"));
    EXPECT_EQ(status()->registered, 3u);
}

TEST_F(CampaignDamage, AStoneResultNamingAScanThatDoesNotExistIsNamedAndCleared) {
    ASSERT_TRUE(open()->save_stone_result(
        0, R"({"scans":[{"id":9,"placed":true,"pose":[1,0,0,0,0,1,0,0,0,0,1,0,0,0,0,1],)"
           R"("reason":"","warning":""}]})"));
    EXPECT_THAT(status().error().message, HasSubstr("stone 0: the stone's result is damaged"));
    EXPECT_THAT(status().error().message, HasSubstr("names scan 9 of 5"));
    ASSERT_TRUE(open()->save_stone_result(0, R"({"scans":[{"id":1e300}]})"));
    EXPECT_THAT(status().error().message, HasSubstr("a scan id is not a whole number"));
    EXPECT_EQ(check(false).issues.at(0).kind, "stone-result");
    EXPECT_TRUE(check(true).clean());
    EXPECT_EQ(status()->stones_done, 0u);
}

TEST_F(CampaignDamage, ADamagedSummarySetsItsScanBackToNewAndTheJobPreparesOnlyThatScan) {
    sql(R"(UPDATE scans SET summary_json = '{"points":30,"centre_m":[1,"a",3]}' WHERE id = 3)");
    EXPECT_THAT(job().error().message, HasSubstr("campaign.sqlite: scan 3: the prepared summary"));
    const CampaignCheckReport found = check(false);
    ASSERT_EQ(found.unresolved(), 1u);
    EXPECT_EQ(found.issues[0].kind, "scan-record");
    EXPECT_TRUE(check(true).clean());
    const auto tasks = job();
    ASSERT_TRUE(tasks) << tasks.error().message;
    ASSERT_GE(tasks->size(), 1u);
    EXPECT_EQ((*tasks)[0].kind, CampaignTaskKind::kPrepare);
    EXPECT_EQ((*tasks)[0].id, 3);
}

TEST_F(CampaignDamage, ADamagedMatchGraphIsClearedAndTheStonesAreFoundAgain) {
    ASSERT_TRUE(open()->set_value("graph", R"({"warnings":{"x":1})"));
    EXPECT_THAT(job().error().message, HasSubstr("the match graph is damaged"));
    EXPECT_EQ(check(false).issues.at(0).kind, "match-graph");
    EXPECT_TRUE(check(true).clean());
    EXPECT_EQ(status()->stones, 0u);
    EXPECT_TRUE(job());  // The graph stage runs on the owner: stones are found again.
    EXPECT_GE(status()->stones, 1u);
    EXPECT_EQ(status()->stones_done, 0u);  // Their multi-view tasks were handed out.
}

TEST_F(CampaignDamage, TablesThatContradictEachOtherAreReportedAndNotRepaired) {
    sql("UPDATE pairs SET target = 9 WHERE source = 2");
    const auto s = status();
    ASSERT_FALSE(s);
    EXPECT_THAT(s.error().message,
                HasSubstr("the pairs table is damaged: pair 2-9 does not name two of the 5 scans"));
    const CampaignCheckReport repaired = check(true);
    EXPECT_FALSE(repaired.clean());
    EXPECT_EQ(repaired.issues.at(0).kind, "database");
    sql("UPDATE pairs SET source = 1.5 WHERE source = 1");  // Read as 1, matched by no repair.
    EXPECT_THAT(status().error().message, HasSubstr("name a scan by a value that is not a whole"));
    sql("DELETE FROM scans WHERE id = 1");
    EXPECT_THAT(status().error().message, HasSubstr("row 1 holds scan id 2"));
}

}  // namespace
}  // namespace anascan::acquisition
