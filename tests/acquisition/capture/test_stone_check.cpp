// check_stone_of_scan on a real session store: three strips of one relief stored as the
// model (group 0), and a fourth strip of the same relief as the scan to decide on, in each
// state the registrar can leave it in. A fit the registrar made and then took back (a
// flagged scan) is evidence of another object, whatever the pose-free signals say: a
// smaller stone of the same kind passes them.
#include <gtest/gtest.h>

#include <filesystem>

#include "../session_test_support.hpp"
#include "../strip_session.hpp"
#include "anascan/acquisition/capture/stone_check.hpp"

namespace anascan::acquisition {
namespace {

namespace fs = std::filesystem;

class StoneCheckOfScan : public testing_util::SessionFolder {
protected:
    /// The four strips, the first three registered in group 0 at their true poses (the
    /// model), the fourth as `last`.
    std::unique_ptr<SessionStore> session_with_last(const RegistrationUpdate& last) {
        fs::remove_all(dir_);
        return testing_util::session_of_strips(dir_, [&](int k) {
            return k < 3 ? RegistrationUpdate{.state = ScanState::kRegistered,
                                              .group = 0,
                                              .pose = Pose::Identity(),
                                              .quality_json = "{}"}
                         : last;
        });
    }
};

TEST_F(StoneCheckOfScan, AScanJoinedToTheModelIsOfTheStone) {
    auto store =
        session_with_last({.state = ScanState::kRegistered, .group = 0, .pose = Pose::Identity()});
    auto check = check_stone_of_scan(*store, 4);
    ASSERT_TRUE(check.has_value()) << check.error().message;
    EXPECT_EQ(check->outcome, StoneCheckOutcome::kJoined) << check->message;
}

TEST_F(StoneCheckOfScan, AScanThatJoinedNothingButFitsTheStoneIsNotCalledAnotherObject) {
    auto store = session_with_last(
        {.state = ScanState::kFailed, .group = 1, .quality_json = R"({"reason":"no match"})"});
    auto check = check_stone_of_scan(*store, 4);
    ASSERT_TRUE(check.has_value()) << check.error().message;
    EXPECT_NE(check->outcome, StoneCheckOutcome::kOtherStone) << check->message;
    EXPECT_NE(check->outcome, StoneCheckOutcome::kJoined) << check->message;
    EXPECT_TRUE(check->contradiction.empty()) << check->contradiction;
}

TEST_F(StoneCheckOfScan, AFitTheRegistrarTookBackAsContradictingTheStoneIsAnotherObject) {
    const std::string reason =
        "scan 4 FLAGGED and taken out of group 0: contradicts its group (disagrees with 3 of 3 "
        "overlapping scans): 38 % of its points lie in the space scan 1's sensor saw empty";
    auto store = session_with_last(
        {.state = ScanState::kFlagged,
         .group = 0,
         .pose = Pose::Identity(),
         .quality_json = R"({"disagreement":"free space","reason":")" + reason + "\"}"});
    auto check = check_stone_of_scan(*store, 4);
    ASSERT_TRUE(check.has_value()) << check.error().message;
    EXPECT_EQ(check->outcome, StoneCheckOutcome::kOtherStone) << check->message;
    EXPECT_EQ(check->model_group, 0);
    EXPECT_GE(check->model_scan, 1);
    EXPECT_LE(check->model_scan, 3) << "a scan of the model";
    EXPECT_EQ(check->contradiction, reason);
    EXPECT_NE(check->message.find("contradicts the stone"), std::string::npos) << check->message;
    EXPECT_NE(check->message.find("38 %"), std::string::npos) << "the evidence: " << check->message;
    EXPECT_NE(check->message.find("m across"), std::string::npos)
        << "the sizes: " << check->message;
}

// A fit taken back because its surface lies a fraction of a millimetre off the stone's is the
// stone's own view that slid (the same stone seen again was taken out so), not another object.
TEST_F(StoneCheckOfScan, AFitTakenBackForASmallOffsetIsNotCalledAnotherObject) {
    auto store = session_with_last(
        {.state = ScanState::kFlagged,
         .group = 0,
         .pose = Pose::Identity(),
         .quality_json = R"j({"disagreement":"surfaces apart",)j"
                         R"j("reason":"contradicts its group (disagrees with 5 of 12 )j"
                         R"j(overlapping scans): scan 4 disagrees with scan 2: its surface lies )j"
                         R"j(0.17 mm (median of 2978 near points) from the other's"})j"});
    auto check = check_stone_of_scan(*store, 4);
    ASSERT_TRUE(check.has_value()) << check.error().message;
    EXPECT_NE(check->outcome, StoneCheckOutcome::kOtherStone) << check->message;
    EXPECT_TRUE(check->contradiction.empty()) << check->contradiction;
    auto later = check_later_scan(*store, 4, 1);
    ASSERT_TRUE(later.has_value()) << later.error().message;
    EXPECT_EQ(later->outcome, StoneCheckOutcome::kUndecided) << later->message;
}

// Later scans of a capture whose first scan joined nothing: still undecided while they stay
// apart from the model, the stone once one joins the model's group, another object once the
// registrar fits one onto the model and takes it back.
TEST_F(StoneCheckOfScan, ALaterScanIsTheStoneOnceItJoinsTheModelAndAnotherObjectIfTakenBack) {
    auto apart = session_with_last({.state = ScanState::kRegistered,
                                    .group = 7,
                                    .pose = Pose::Identity(),
                                    .quality_json = "{}"});
    auto check = check_later_scan(*apart, 4, 1);
    ASSERT_TRUE(check.has_value()) << check.error().message;
    EXPECT_EQ(check->outcome, StoneCheckOutcome::kUndecided) << check->message;
    EXPECT_EQ(check->model_group, 0);
    apart.reset();

    auto joined =
        session_with_last({.state = ScanState::kRegistered, .group = 0, .pose = Pose::Identity()});
    check = check_later_scan(*joined, 4, 2);
    ASSERT_TRUE(check.has_value()) << check.error().message;
    EXPECT_EQ(check->outcome, StoneCheckOutcome::kJoined) << check->message;
    joined.reset();

    auto taken_back = session_with_last(
        {.state = ScanState::kFlagged,
         .group = 0,
         .pose = Pose::Identity(),
         .quality_json = R"j({"disagreement":"normals cross",)j"
                         R"j("reason":"disagrees with 3 of 3: normals cross on 40 %"})j"});
    check = check_later_scan(*taken_back, 4, 1);
    ASSERT_TRUE(check.has_value()) << check.error().message;
    EXPECT_EQ(check->outcome, StoneCheckOutcome::kOtherStone) << check->message;
    EXPECT_NE(check->message.find("normals cross on 40 %"), std::string::npos) << check->message;
    EXPECT_EQ(check->model_group, 0);

    EXPECT_FALSE(check_later_scan(*taken_back, 4, 99).has_value()) << "no such model scan";
}

// What a refused capture sets aside: its scans outside the model, whatever their state,
// but not the session's earlier scans, the capture's scans that joined the model, or scans
// excluded already.
TEST(ScansOutsideModel, AreTheCapturesScansNotInTheModel) {
    const auto scan = [](std::int64_t seq, ScanState state, int group, bool excluded = false) {
        ScanRecord r;
        r.seq = seq;
        r.state = state;
        r.group = group;
        r.excluded = excluded;
        if (state == ScanState::kRegistered) r.pose = Pose::Identity();
        return r;
    };
    const std::vector<ScanRecord> scans{
        scan(1, ScanState::kRegistered, 0),       scan(2, ScanState::kFailed, 1),
        scan(3, ScanState::kRegistered, 2),       scan(4, ScanState::kFlagged, 0),
        scan(5, ScanState::kRegistered, 0),       scan(6, ScanState::kRegistered, 3),
        scan(7, ScanState::kRegistered, 3, true), scan(8, ScanState::kQueued, -1)};
    EXPECT_EQ(scans_outside_model(scans, 2, 0), (std::vector<std::int64_t>{3, 4, 6, 8}));
    EXPECT_EQ(scans_outside_model(scans, 8, 0), (std::vector<std::int64_t>{}));
    EXPECT_EQ(scans_outside_model(scans, 0, 3), (std::vector<std::int64_t>{1, 2, 3, 4, 5, 8}));
}

}  // namespace
}  // namespace anascan::acquisition
