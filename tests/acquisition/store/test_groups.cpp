// The one largest-group rule: the group with the most registered, non-excluded scans with a
// pose, the lowest id on a tie.
#include <gtest/gtest.h>

#include "anascan/acquisition/store/groups.hpp"

namespace anascan::acquisition {
namespace {

ScanRecord record(int group, ScanState state = ScanState::kRegistered, bool excluded = false) {
    ScanRecord r;
    r.group = group;
    r.state = state;
    r.excluded = excluded;
    if (state == ScanState::kRegistered) r.pose = Pose::Identity();
    return r;
}

TEST(LargestGroup, MostMembersLowestIdOnATie) {
    EXPECT_EQ(largest_group_id(std::vector<int>{}), -1);
    EXPECT_EQ(largest_group_id(std::vector<int>{-1, -1}), -1);
    EXPECT_EQ(largest_group_id(std::vector<int>{4, 2, 4, 2}), 2);
    EXPECT_EQ(largest_group_id(std::vector<int>{5, 1, 5, -1, -1, -1}), 5);
}

// A record can be registered and excluded at once (exclusion is undoable, the registration
// stays): it must not count, whatever its state says.
TEST(LargestGroup, ExcludedScansDoNotCount) {
    const std::vector<ScanRecord> scans = {record(0), record(0, ScanState::kRegistered, true),
                                           record(0, ScanState::kRegistered, true), record(1),
                                           record(1)};
    EXPECT_EQ(largest_group(scans), 1);
}

TEST(LargestGroup, FailedQueuedAndPoselessScansDoNotCount) {
    std::vector<ScanRecord> scans = {record(0), record(1), record(1, ScanState::kFailed),
                                     record(1, ScanState::kQueued), record(1)};
    scans.back().pose.reset();
    EXPECT_EQ(largest_group(scans), 0);
    EXPECT_EQ(largest_group({}), -1);
}

// The rb1 case of the capture: 12 scans, 8 flagged, 2 alone, and a pair as the model.
TEST(ModelMembers, APairOutOfManyIsUnconfirmedAndFlaggedScansAreCounted) {
    std::vector<ScanRecord> scans;
    for (int k = 0; k < 12; ++k) scans.push_back(record(k, ScanState::kFlagged));
    scans[0] = record(0);
    scans[1] = record(1);
    scans[2] = record(2);
    scans[3] = record(1);
    for (std::size_t k = 0; k < scans.size(); ++k) scans[k].seq = static_cast<std::int64_t>(k + 1);
    const ModelMembers m = model_members(scans);
    EXPECT_EQ(m.joined, (std::vector<std::int64_t>{2, 4}));
    EXPECT_EQ(m.active, 12u);
    EXPECT_EQ(m.flagged, 8u);
    EXPECT_EQ(m.strength(), ModelStrength::kUnconfirmedPair);
}

TEST(ModelMembers, StrengthFollowsTheShareOfScansInTheModel) {
    const auto strength = [](std::vector<ScanRecord> scans) {
        return model_members(scans).strength();
    };
    EXPECT_EQ(strength({record(0), record(1)}), ModelStrength::kNone);
    EXPECT_EQ(strength({record(0), record(0)}), ModelStrength::kWhole);  // the only two
    EXPECT_EQ(strength({record(0), record(0), record(1)}), ModelStrength::kUnconfirmedPair);
    // An excluded scan is not part of the session's question.
    EXPECT_EQ(strength({record(0), record(0), record(1, ScanState::kRegistered, true)}),
              ModelStrength::kWhole);
    EXPECT_EQ(strength({record(0), record(0), record(0), record(1), record(2), record(3),
                        record(4, ScanState::kFailed)}),
              ModelStrength::kPartial);  // 3 of 7
    EXPECT_EQ(strength({record(0), record(0), record(0), record(1), record(2), record(3)}),
              ModelStrength::kWhole);  // 3 of 6: half
}

}  // namespace
}  // namespace anascan::acquisition
