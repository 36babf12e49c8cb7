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

}  // namespace
}  // namespace anascan::acquisition
