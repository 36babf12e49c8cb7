// union_pulls: a scan displaced along its surface is moved back by the rest of its group at
// once; the scans where they belong stay; too small a group is not judged.
#include <gtest/gtest.h>

#include <cstdio>

#include "../test_bumpy_surface.hpp"
#include "anascan/processing/evaluation/union_pull.hpp"

namespace anascan {
namespace {

/// Four overlapping strips of one relief, each 8 cm long, 4 cm apart, in the group frame.
std::vector<PointCloud> strips() {
    const std::vector<testing_util::Bump> bumps = testing_util::random_bumps(11, 40);
    std::vector<PointCloud> out;
    for (int k = 0; k < 4; ++k) {
        const double x0 = -0.1 + 0.04 * k;
        out.push_back(testing_util::bumpy_surface(bumps, x0, x0 + 0.08, 0.001, 0.0003 * k));
    }
    return out;
}

std::vector<ConsistencyScan> group_of(const std::vector<PointCloud>& clouds) {
    std::vector<ConsistencyScan> scans;
    for (const PointCloud& c : clouds) scans.push_back({.cloud = &c});
    return scans;
}

TEST(UnionPull, AScanSlidAlongTheSurfaceIsPulledBackAndTheOthersAreHeld) {
    const std::vector<PointCloud> clouds = strips();
    std::vector<ConsistencyScan> scans = group_of(clouds);
    const Eigen::Vector3d slide(0.0, 0.008, 0.0);
    scans[1].T_group_scan = Pose(Eigen::Translation3d(slide));
    const std::vector<ScanPull> pulls = union_pulls(scans);
    ASSERT_EQ(pulls.size(), 4u);
    EXPECT_TRUE(pulls[1].judged);
    EXPECT_TRUE(pulls[1].pulled);
    EXPECT_NEAR(pulls[1].moved_m, slide.norm(), 0.001);
    for (const std::size_t k : {0u, 2u, 3u}) {
        EXPECT_TRUE(pulls[k].judged) << k;
        EXPECT_FALSE(pulls[k].pulled) << k << ": " << pulls[k].moved_m;
    }
}

TEST(UnionPull, AGroupWhereEveryScanIsInPlaceHasNoPull) {
    const std::vector<PointCloud> clouds = strips();
    const std::vector<ScanPull> pulls = union_pulls(group_of(clouds));
    for (const ScanPull& p : pulls) {
        std::printf("moved %.3f mm, rms %.3f -> %.3f mm, overlap %.2f\n", p.moved_m * 1e3,
                    p.rms_before_m * 1e3, p.rms_m * 1e3, p.overlap_fraction);
        EXPECT_TRUE(p.judged);
        EXPECT_FALSE(p.pulled);
    }
}

TEST(UnionPull, TwoScansAreNotJudged) {
    std::vector<PointCloud> clouds = strips();
    clouds.resize(2);
    std::vector<ConsistencyScan> scans = group_of(clouds);
    scans[1].T_group_scan = Pose(Eigen::Translation3d(0.0, 0.008, 0.0));
    for (const ScanPull& p : union_pulls(scans)) EXPECT_FALSE(p.judged);
}

}  // namespace
}  // namespace anascan
