// The pure campaign stages: descriptors (pose-free keys, featureless scans), candidate
// pairs from shared keys, stones from verified pairs.
#include <gtest/gtest.h>

#include <algorithm>
#include <iterator>

#include "anascan/processing/campaign/campaign_stages.hpp"
#include "test_bumpy_surface.hpp"

namespace anascan {
namespace {

using testing_util::bumpy_surface;
using testing_util::random_bumps;

double shared_fraction(const std::vector<std::uint64_t>& a, const std::vector<std::uint64_t>& b) {
    std::vector<std::uint64_t> common;
    std::set_intersection(a.begin(), a.end(), b.begin(), b.end(), std::back_inserter(common));
    return static_cast<double>(common.size()) / static_cast<double>(std::min(a.size(), b.size()));
}

TEST(CampaignDescriptor, KeysDoNotDependOnThePose) {
    const PointCloud surface = bumpy_surface(random_bumps(3, 40), -0.1, 0.1, 0.002, 0.0);
    const Pose T = Pose(Eigen::AngleAxisd(1.1, Eigen::Vector3d(1, 2, 3).normalized())) *
                   Eigen::Translation3d(0.3, -0.2, 0.5);
    const CampaignConfig config;
    const double spacing_m = median_sample_spacing_m(surface);
    const ScanDescriptor a = describe_campaign_scan(surface, spacing_m, config);
    const ScanDescriptor b = describe_campaign_scan(transformed(surface, T), spacing_m, config);
    ASSERT_TRUE(a.problem.empty()) << a.problem;
    ASSERT_GT(a.keys.size(), 50u);
    EXPECT_GT(shared_fraction(a.keys, b.keys), 0.5);  // Sites are sampled on a grid of the frame.
    const ScanDescriptor other = describe_campaign_scan(
        bumpy_surface(random_bumps(17, 40), -0.1, 0.1, 0.002, 0.0), spacing_m, config);
    EXPECT_LT(shared_fraction(a.keys, other.keys), 0.5 * shared_fraction(a.keys, b.keys));
}

TEST(CampaignDescriptor, APlaneHasNoKeysAndSaysWhy) {
    const PointCloud plane = bumpy_surface({}, -0.1, 0.1, 0.002, 0.0);
    const ScanDescriptor d = describe_campaign_scan(plane, 0.002, {});
    EXPECT_TRUE(d.keys.empty());
    EXPECT_NE(d.problem.find("featureless"), std::string::npos) << d.problem;
}

TEST(CampaignCandidates, ScansSharingKeysArePairedOthersNot) {
    // Two groups of three scans; keys shared within a group only.
    std::vector<std::vector<std::uint64_t>> keys(6);
    for (std::uint64_t k = 0; k < 100; ++k) {
        for (std::size_t s = 0; s < 6; ++s) {
            const std::uint64_t group = s / 3;
            if ((k + s) % 3 != 0) keys[s].push_back(1000 * (group + 1) + k);
        }
    }
    for (auto& k : keys) std::sort(k.begin(), k.end());
    const std::vector<CandidatePair> pairs = propose_candidates(keys, {.candidates_per_scan = 2});
    ASSERT_EQ(pairs.size(), 6u);  // Every pair within each group, none across.
    for (const CandidatePair& p : pairs) {
        EXPECT_EQ(p.source / 3, p.target / 3);
        EXPECT_GT(p.source, p.target);
        EXPECT_GT(p.similarity, 0.0);
    }
}

TEST(CampaignStones, ComponentsOfVerifiedPairsUnderTheGate) {
    const auto pair = [](std::size_t s, std::size_t t, bool verified, double rms_m) {
        return RegisteredPair{
            s, t, {.verified = verified, .rms_m = rms_m, .target_spacing_m = 0.001}};
    };
    const std::vector<RegisteredPair> pairs = {
        pair(1, 0, true, 1e-4),   pair(2, 1, true, 1.2e-4), pair(4, 3, true, 1.1e-4),
        pair(5, 4, true, 0.9e-4), pair(3, 2, true, 2e-3),  // A look-alike fit far above the rest.
        pair(6, 5, false, 1e-4)};
    const StoneGraph graph = find_stones(8, pairs, {});
    ASSERT_EQ(graph.stones.size(), 2u);
    EXPECT_EQ(graph.stones[0], (std::vector<std::size_t>{0, 1, 2}));
    EXPECT_EQ(graph.stones[1], (std::vector<std::size_t>{3, 4, 5}));
    EXPECT_EQ(graph.gated_pairs, 1u);
    EXPECT_EQ(graph.stone_of_scan[6], -1);
    EXPECT_EQ(graph.stone_of_scan[7], -1);
}

}  // namespace
}  // namespace anascan
