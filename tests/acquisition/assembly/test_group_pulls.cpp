// group_pulls / flag_pulled on a real session store: strips of one relief stored as the
// scans of one group, one of them placed 8 mm off along the surface; a missing scan file.
#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>

#include "../session_test_support.hpp"
#include "../strip_session.hpp"
#include "anascan/acquisition/assembly/group_pulls.hpp"

namespace anascan::acquisition {
namespace {

namespace fs = std::filesystem;

class GroupPulls : public testing_util::SessionFolder {
protected:
    /// The four strips all in group 0 at their true poses, except `slid_seq`, moved 8 mm
    /// along the surface.
    std::unique_ptr<SessionStore> session_with_strips(std::int64_t slid_seq) {
        return testing_util::session_of_strips(dir_, [&](int k) {
            Pose T = Pose::Identity();
            if (k + 1 == slid_seq) T.translation() = Eigen::Vector3d(0.0, 0.008, 0.0);
            return RegistrationUpdate{
                .state = ScanState::kRegistered, .group = 0, .pose = T, .quality_json = "{}"};
        });
    }
};

TEST_F(GroupPulls, TheSlidScanIsPulledFlaggedAndLeavesTheGroup) {
    auto store = session_with_strips(2);
    auto pulls = group_pulls(*store);
    ASSERT_TRUE(pulls.has_value()) << pulls.error().message;
    ASSERT_EQ(pulls->size(), 4u);
    for (const GroupPull& p : *pulls) {
        EXPECT_EQ(p.group, 0);
        EXPECT_EQ(p.group_scans, 4u);
        // The middle strips overlap the others on both sides (the end strips hang off the
        // bowl's rim by half and may not be judged).
        if (p.seq == 2 || p.seq == 3) {
            EXPECT_TRUE(p.pull.judged) << p.seq;
        }
        EXPECT_EQ(p.pull.pulled, p.seq == 2) << p.seq << ": " << p.pull.moved_m;
    }
    auto flagged = flag_pulled(*store, *pulls);
    ASSERT_TRUE(flagged.has_value());
    EXPECT_EQ(*flagged, 1u);
    const auto scans = store->scans();
    ASSERT_TRUE(scans.has_value());
    EXPECT_EQ((*scans)[1].state, ScanState::kFlagged);
    const auto events = store->events();
    ASSERT_TRUE(events.has_value());
    EXPECT_TRUE(std::any_of(events->begin(), events->end(), [](const EventRecord& e) {
        return e.kind == "registration-flagged" && e.message.find("scan 2 FLAGGED") == 0;
    }));
    // The rest of the group holds together: nothing is pulled any more.
    auto again = group_pulls(*store);
    ASSERT_TRUE(again.has_value());
    ASSERT_EQ(again->size(), 3u);
    for (const GroupPull& p : *again) EXPECT_FALSE(p.pull.pulled) << p.seq;
}

TEST_F(GroupPulls, AMissingScanFileIsAnErrorNamingIt) {
    auto store = session_with_strips(0);
    const auto scans = store->scans();
    ASSERT_TRUE(scans.has_value());
    fs::remove(dir_ / (*scans)[2].file);
    auto pulls = group_pulls(*store);
    ASSERT_FALSE(pulls.has_value());
    EXPECT_NE(pulls.error().message.find("scan_000003"), std::string::npos)
        << pulls.error().message;
}

}  // namespace
}  // namespace anascan::acquisition
