// Slide probes of the pairwise verification (GlobalRegistrationConfig::
// slide_probe_max_eigenvalue_ratio): a grooved bar on the ground, seen twice, is fixed
// along its length only by its end face and shallow grooves of 30 mm period. A hypothesis
// slid by one period fits the grooves, the sides and the ground; the end face falls beyond
// the correspondence gate, so the refinement stays there and verifies. With the probes the
// pair ends either at the true pose or ambiguous with the slide named, never a silent
// success 30 mm off.
#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <cmath>
#include <numbers>
#include <random>

#include "anascan/processing/core/point_cloud.hpp"
#include "anascan/processing/registration/batch/scan_registration.hpp"
#include "anascan/processing/registration/global/global_registration.hpp"
#include "registration/batch/steps.hpp"
#include "registration/global/steps.hpp"

namespace anascan {
namespace {

constexpr double kPeriodM = 0.03;  // Grooves across the bar's top.
constexpr double kDepthM = 0.003;  // Groove depth.
constexpr double kHalfLengthM = 0.1;
constexpr double kHalfWidthM = 0.02;
constexpr double kHeightM = 0.03;

void add(PointCloud& cloud, double x, double y, double z, const Eigen::Vector3d& n,
         std::mt19937& rng, double noise_m) {
    std::normal_distribution<double> noise(0.0, noise_m);
    const Eigen::Vector3d p = Eigen::Vector3d(x, y, z) + noise(rng) * n;
    cloud.positions.push_back(p.cast<float>());
    cloud.normals.push_back(n.normalized().cast<float>());
}

double top_z(double x) {
    return kHeightM - kDepthM * (0.5 + 0.5 * std::cos(2.0 * std::numbers::pi * x / kPeriodM));
}

/// The ground around the bar, its grooved top, both long sides and the end face at +x
/// (what a sensor above the +x end sees), sampled every `step_m` from `offset_m`.
PointCloud grooved_bar(double step_m, double offset_m, double noise_m, unsigned seed) {
    std::mt19937 rng(seed);
    PointCloud cloud;
    const double k = 2.0 * std::numbers::pi / kPeriodM;
    for (double x = -0.15 + offset_m; x < 0.15; x += step_m) {
        for (double y = -0.08 + offset_m; y < 0.08; y += step_m) {
            const bool on_bar = std::abs(x) < kHalfLengthM && std::abs(y) < kHalfWidthM;
            if (!on_bar) {
                add(cloud, x, y, 0.0, Eigen::Vector3d::UnitZ(), rng, noise_m);
                continue;
            }
            const double slope = 0.5 * kDepthM * k * std::sin(k * x);  // dz/dx of the top.
            add(cloud, x, y, top_z(x), Eigen::Vector3d(-slope, 0.0, 1.0), rng, noise_m);
        }
        if (std::abs(x) >= kHalfLengthM) continue;
        for (double z = offset_m; z < top_z(x); z += step_m) {
            add(cloud, x, kHalfWidthM, z, Eigen::Vector3d::UnitY(), rng, noise_m);
            add(cloud, x, -kHalfWidthM, z, -Eigen::Vector3d::UnitY(), rng, noise_m);
        }
    }
    for (double y = -kHalfWidthM + offset_m; y < kHalfWidthM; y += step_m) {
        for (double z = offset_m; z < top_z(kHalfLengthM); z += step_m) {
            add(cloud, kHalfLengthM, y, z, Eigen::Vector3d::UnitX(), rng, noise_m);
        }
    }
    return cloud;
}

struct BarPair {
    PointCloud source, target;
    std::vector<ScanFeatures> features;
};

BarPair bar_pair(const GlobalRegistrationConfig& config) {
    BarPair pair{.source = grooved_bar(0.0015, 0.0007, 0.0001, 1),
                 .target = grooved_bar(0.0015, 0.0, 0.0001, 2)};
    const PointCloud* const both[] = {&pair.source, &pair.target};
    const InvariantRadii radii_m = registration_radii_m(both, config);
    std::vector<IntegralInvariantResult> invariants = {describe_scan(pair.source, radii_m, config),
                                                       describe_scan(pair.target, radii_m, config)};
    const double spacings_m[] = {0.0015, 0.0015};
    pair.features = scan_features(std::move(invariants), spacings_m, config);
    return pair;
}

/// Refines and verifies one hypothesis: the true pose slid by one groove period.
GlobalRegistrationResult register_slid(const BarPair& pair,
                                       const GlobalRegistrationConfig& config) {
    FeatureMatchingResult matching;
    matching.hypotheses.push_back(
        {.T_target_source = Pose(Eigen::Translation3d(-kPeriodM, 0.0, 0.0)), .score = 10.0});
    return detail::refine_and_verify({pair.source, pair.features[0], std::nullopt},
                                     {pair.target, pair.features[1], std::nullopt},
                                     std::move(matching), config);
}

TEST(SlideProbes, APoseSlidAlongAWeakDirectionIsNeverASilentSuccess) {
    GlobalRegistrationConfig config;
    const BarPair pair = bar_pair(config);
    ASSERT_EQ(pair.features[0].patches.status, FeaturePatchStatus::kOk);
    ASSERT_EQ(pair.features[1].patches.status, FeaturePatchStatus::kOk);

    // Without the probes the slid pose verifies: the case the rule is for.
    config.slide_probe_max_eigenvalue_ratio = 0.0;
    const GlobalRegistrationResult unprobed = register_slid(pair, config);
    ASSERT_EQ(unprobed.status, GlobalRegistrationStatus::kSuccess);
    const double unprobed_error_m = unprobed.T_target_source.translation().norm();
    EXPECT_GT(unprobed_error_m, 0.02);
    EXPECT_LT(unprobed.hypotheses.front().fine.degeneracy.eigenvalue_ratio, 0.02);
    EXPECT_EQ(unprobed.slide_probes, 0u);

    config.slide_probe_max_eigenvalue_ratio =
        GlobalRegistrationConfig{}.slide_probe_max_eigenvalue_ratio;
    const GlobalRegistrationResult probed = register_slid(pair, config);
    EXPECT_EQ(probed.slide_probes, 4u);
    const double error_m = probed.T_target_source.translation().norm();
    std::printf(
        "unprobed: %.1f mm off, ratio %.1e; probed: %s, %.1f mm off, %s\n", unprobed_error_m * 1e3,
        unprobed.hypotheses.front().fine.degeneracy.eigenvalue_ratio,
        std::string(to_string(probed.status)).c_str(), error_m * 1e3, probed.message.c_str());
    if (probed.status == GlobalRegistrationStatus::kSuccess) {
        EXPECT_LT(error_m, 0.001);  // The true pose won.
    } else {
        ASSERT_EQ(probed.status, GlobalRegistrationStatus::kAmbiguous);
        EXPECT_TRUE(probed.slide_ambiguous);
        EXPECT_GT(probed.slide_m, 0.02);
        EXPECT_NE(probed.message.find("slid by up to"), std::string::npos);
        EXPECT_GT(std::abs(probed.slide_direction.x()), 0.9);  // Along the bar.
    }
}

PairOutcome link(std::size_t source, std::size_t target, FineRegistrationStatus status,
                 double ratio) {
    return {.source = source,
            .target = target,
            .fine = {.status = status,
                     .eigenvalue_ratio = ratio,
                     .weakest_translation = Eigen::Vector3d::UnitX()},
            .linked = true};
}

// A placed scan all of whose links ended still moving along a weak direction is warned
// about (ScanRegistrationConfig::sliding_link_max_eigenvalue_ratio); one converged link, a
// well constrained link or the rule off give no warning.
TEST(SlideProbes, AScanWhoseLinksAllEndStillSlidingGetsAWarning) {
    using enum FineRegistrationStatus;
    ScanRegistrationResult result;
    for (int i = 0; i < 4; ++i) {
        result.scans.push_back({.name = "scan " + std::to_string(i), .placed = true});
    }
    result.scans[2].T_world_scan =
        Pose(Eigen::AngleAxisd(std::numbers::pi / 2, Eigen::Vector3d::UnitZ()));
    result.pairs = {link(1, 0, kConverged, 0.01),       // Settled.
                    link(2, 0, kMaxIterations, 0.004),  // Scan 2's two links: still sliding.
                    link(3, 2, kMaxIterations, 0.002),
                    link(3, 1, kMaxIterations, 0.5)};  // Scan 3's other link is well fixed.
    ScanRegistrationConfig config;
    detail::warn_sliding_scans(config, result);
    EXPECT_EQ(result.scans[0].warning, "");  // 1-0 converged, 2-0 sliding.
    EXPECT_EQ(result.scans[1].warning, "");
    EXPECT_EQ(result.scans[3].warning, "");
    const std::string& w = result.scans[2].warning;
    EXPECT_NE(w.find("not fixed by its overlaps"), std::string::npos) << w;
    EXPECT_NE(w.find("2 links"), std::string::npos) << w;
    EXPECT_NE(w.find("0.0020"), std::string::npos) << w;
    // The weakest link (3-2) slides along x of scan 2, which is turned by 90°: world y.
    EXPECT_NE(w.find("(0.00, 1.00, 0.00)"), std::string::npos) << w;

    result.scans[2].warning.clear();
    config.sliding_link_max_eigenvalue_ratio = 0.0;
    detail::warn_sliding_scans(config, result);
    EXPECT_EQ(result.scans[2].warning, "");
}

// A placed scan kept by one link only (of three or more placed scans) is warned about: no
// second scan confirms its pose; a closed loop confirms every scan; dropped links do not
// count.
TEST(SlideProbes, AScanThatNoSecondScanConfirmsGetsAWarning) {
    using enum FineRegistrationStatus;
    ScanRegistrationResult result;
    for (int i = 0; i < 3; ++i) {
        result.scans.push_back({.name = "scan " + std::to_string(i), .placed = true});
    }
    result.placed_count = 3;
    result.pairs = {link(1, 0, kConverged, 0.5), link(2, 1, kConverged, 0.5)};
    detail::warn_unconfirmed_scans(result);
    EXPECT_NE(result.scans[0].warning.find("one link only"), std::string::npos);
    EXPECT_EQ(result.scans[1].warning, "");
    EXPECT_NE(result.scans[2].warning.find("one link only"), std::string::npos);

    for (ScanOutcome& scan : result.scans) scan.warning.clear();
    result.pairs.push_back(link(2, 0, kConverged, 0.5));
    detail::warn_unconfirmed_scans(result);
    for (const ScanOutcome& scan : result.scans) EXPECT_EQ(scan.warning, "") << scan.name;

    result.pairs.back().link_dropped = true;
    detail::warn_unconfirmed_scans(result);
    EXPECT_NE(result.scans[2].warning.find("one link only"), std::string::npos);
}

}  // namespace
}  // namespace anascan
