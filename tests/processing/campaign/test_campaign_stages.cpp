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
    EXPECT_GE(shared_fraction(a.keys, b.keys), 0.9);  // Keypoints follow the surface.
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

std::vector<PreparedSummary> summaries(std::size_t n) {
    std::vector<PreparedSummary> out(n);
    for (PreparedSummary& s : out) {
        s.spacing_m = 0.001;
        s.centre_m = Eigen::Vector3d(0.1, 0.05, 0.2);
    }
    return out;
}

RegisteredPair verified_pair(std::size_t s, std::size_t t, double rms_m, const Pose& T_t_s) {
    return RegisteredPair{
        s,
        t,
        {.verified = true, .T_target_source = T_t_s, .rms_m = rms_m, .target_spacing_m = 0.001}};
}

// Scan poses in their stone's frame (any; the graph only sees relative poses).
Pose scan_pose(std::size_t i) {
    return Pose(Eigen::AngleAxisd(0.3 * static_cast<double>(i), Eigen::Vector3d::UnitZ())) *
           Eigen::Translation3d(0.01 * static_cast<double>(i), 0.0, 0.0);
}

RegisteredPair true_pair(std::size_t s, std::size_t t, double rms_m) {
    return verified_pair(s, t, rms_m, scan_pose(t).inverse() * scan_pose(s));
}

const Pose kTurned(Eigen::AngleAxisd(M_PI, Eigen::Vector3d::UnitX()));

TEST(CampaignStones, ComponentsOfVerifiedPairsUnderTheGate) {
    std::vector<RegisteredPair> pairs = {true_pair(1, 0, 1e-4), true_pair(2, 1, 1.2e-4),
                                         true_pair(4, 3, 1.1e-4), true_pair(5, 4, 0.9e-4),
                                         true_pair(3, 2, 2e-3)};  // A look-alike far above.
    pairs.push_back({6, 5, {.verified = false, .rms_m = 1e-4, .target_spacing_m = 0.001}});
    const StoneGraph graph = find_stones(summaries(8), pairs, {});
    ASSERT_EQ(graph.stones.size(), 2u);
    EXPECT_EQ(graph.stones[0], (std::vector<std::size_t>{0, 1, 2}));
    EXPECT_EQ(graph.stones[1], (std::vector<std::size_t>{3, 4, 5}));
    EXPECT_EQ(graph.relative_gated_pairs, 1u);
    EXPECT_EQ(graph.stone_of_scan[6], -1);
    EXPECT_EQ(graph.stone_of_scan[7], -1);
}

TEST(CampaignStones, PerScanGateIsRelativeToEachScansBestPairs) {
    // Scans 0-2 fit at 0.1 mm (a fine scanner), 3-5 at 1 mm (a coarse one): a campaign
    // median (0.55 mm) passes a 0.35 mm look-alike between 2 and 3, which fits 3.5 times
    // worse than scan 2's pairs.
    std::vector<RegisteredPair> pairs = {true_pair(1, 0, 1e-4), true_pair(2, 1, 1e-4),
                                         true_pair(4, 3, 1e-3), true_pair(5, 4, 1.2e-3),
                                         verified_pair(3, 2, 0.35e-3, kTurned)};
    const StoneGraph graph = find_stones(summaries(6), pairs, {});
    ASSERT_EQ(graph.stones.size(), 2u) << graph.relative_gated_pairs;
    EXPECT_EQ(graph.stones[1], (std::vector<std::size_t>{3, 4, 5}));
    EXPECT_EQ(graph.relative_gated_pairs, 1u);
}

TEST(CampaignStones, ATriangleThatDoesNotCloseCutsItsWorstPair) {
    // 0-1-2 a stone; 2-0 fits almost as well but at a turned pose (a near-symmetric block).
    std::vector<RegisteredPair> pairs = {true_pair(1, 0, 1e-4), true_pair(2, 1, 1e-4),
                                         verified_pair(2, 0, 1.5e-4, kTurned)};
    const StoneGraph graph = find_stones(summaries(3), pairs, {});
    EXPECT_EQ(graph.triangle_cut_pairs, 1u);
    ASSERT_EQ(graph.stones.size(), 1u);
    EXPECT_EQ(graph.stones[0].size(), 3u);
    for (const std::string& w : graph.warning_of_scan)
        EXPECT_NE(w.find("triangle"), std::string::npos) << w;
    // A closing triangle cuts nothing and warns of nothing.
    const StoneGraph good =
        find_stones(summaries(3), {pairs[0], pairs[1], true_pair(2, 0, 1.5e-4)}, {});
    EXPECT_EQ(good.triangle_cut_pairs, 0u);
    for (const std::string& w : good.warning_of_scan) EXPECT_TRUE(w.empty()) << w;
}

TEST(CampaignStones, ACycleAgainstBetterPairsCutsAndWarnsOfBothScans) {
    // A chain 0-1-2-3 (no triangles) closed by a look-alike 3-0: cut, 0 and 3 warned. Closed
    // by a true pair, the loop confirms all four.
    std::vector<RegisteredPair> pairs = {true_pair(1, 0, 1e-4), true_pair(2, 1, 1e-4),
                                         true_pair(3, 2, 1e-4),
                                         verified_pair(3, 0, 1.2e-4, kTurned)};
    const StoneGraph graph = find_stones(summaries(4), pairs, {});
    EXPECT_EQ(graph.cycle_cut_pairs, 1u);
    EXPECT_FALSE(graph.warning_of_scan[0].empty());
    EXPECT_FALSE(graph.warning_of_scan[3].empty());
    EXPECT_NE(graph.warning_of_scan[0].find("disagrees"), std::string::npos);
    // What is left is a chain: no loop confirms scan 1 either.
    EXPECT_NE(graph.warning_of_scan[1].find("no loop"), std::string::npos);
    const StoneGraph good =
        find_stones(summaries(4), {pairs[0], pairs[1], pairs[2], true_pair(3, 0, 1.2e-4)}, {});
    EXPECT_EQ(good.cycle_cut_pairs, 0u);
    EXPECT_TRUE(good.warning_of_scan[0].empty());
}

}  // namespace
}  // namespace anascan
