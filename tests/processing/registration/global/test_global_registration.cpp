// Global registration on synthetic shapes: a non-symmetric bumpy surface seen in two
// overlapping windows (different samples), the source moved by known random rigid
// transforms with fixed seeds, must be recovered within 0.5° and 1 mm; two unrelated
// surfaces must not register; bad input is reported. Also checks feature patches.
#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <cmath>
#include <numbers>
#include <random>
#include <vector>

#include "anascan/processing/evaluation/pose_sampling.hpp"
#include "anascan/processing/features/feature_patches.hpp"
#include "anascan/processing/features/integral_invariants.hpp"
#include "anascan/processing/registration/global/global_registration.hpp"
#include "test_bumpy_surface.hpp"

namespace anascan {
namespace {

using testing_util::Bump;
using testing_util::random_bumps;

using testing_util::bumpy_surface;

// The same draw as sample_random_pose from a generator seeded with `seed`.
Pose random_pose(unsigned seed, double max_translation_m) {
    std::mt19937 rng(seed);
    return sample_random_pose(rng, max_translation_m);
}

TEST(FeaturePatch, BumpySurfaceGivesTensOfPatchesWithConsistentFigures) {
    const PointCloud cloud = bumpy_surface(random_bumps(7, 14), -0.1, 0.1, 0.001, 0.0);
    const IntegralInvariantResult invariants =
        compute_integral_invariants(cloud, {.radii_m = radii_for_object_size_m(0.28)});
    const FeaturePatchResult patches = extract_feature_patches(invariants, {});
    ASSERT_EQ(patches.status, FeaturePatchStatus::kOk);
    EXPECT_GE(patches.patches.size(), 20u);
    EXPECT_LE(patches.patches.size(), 400u);
    for (const FeaturePatch& p : patches.patches) {
        EXPECT_GE(p.site_count, 6u);
        EXPECT_NEAR(p.normal.norm(), 1.0, 1e-9);
        EXPECT_GE(p.extent_m[0], p.extent_m[1]);
        EXPECT_GE(p.extent_m[1], p.extent_m[2]);
        if (p.side == CurvatureSide::kConvex) {
            EXPECT_LT(p.mean_volume, 0.5);
        } else {
            EXPECT_GT(p.mean_volume, 0.5);
        }
    }
}

TEST(GlobalRegistration, RecoversRandomRigidMotionsOfABumpySurface) {
    const std::vector<Bump> bumps = random_bumps(11, 14);
    const PointCloud target = bumpy_surface(bumps, -0.1, 0.05, 0.001, 0.0);
    const PointCloud source_in_target = bumpy_surface(bumps, -0.05, 0.1, 0.001, 0.0005);
    for (unsigned seed : {1u, 2u, 3u}) {
        const Pose T_moved_target = random_pose(seed, 0.5);
        const PointCloud source = transformed(source_in_target, T_moved_target);
        const GlobalRegistrationResult result = register_global(source, target, {});
        ASSERT_EQ(result.status, GlobalRegistrationStatus::kSuccess)
            << "seed " << seed << ": " << result.message << ", hypotheses "
            << result.matching.hypotheses.size();
        const PoseDifference error =
            pose_difference(result.T_target_source, T_moved_target.inverse());
        EXPECT_LT(error.rotation_deg, 0.5) << "seed " << seed;
        EXPECT_LT(error.translation_m, 0.001) << "seed " << seed;
        EXPECT_GT(result.source_patches, 10u);
        EXPECT_GT(result.timing.total_s, 0.0);
    }
}

TEST(GlobalRegistration, UnrelatedSurfacesAreNotASuccess) {
    const PointCloud target = bumpy_surface(random_bumps(21, 14), -0.1, 0.05, 0.001, 0.0);
    for (unsigned seed : {4u, 5u}) {
        const PointCloud other =
            bumpy_surface(random_bumps(100 + seed, 14), -0.05, 0.1, 0.001, 0.0005);
        const GlobalRegistrationResult result =
            register_global(transformed(other, random_pose(seed, 0.5)), target, {});
        EXPECT_NE(result.status, GlobalRegistrationStatus::kSuccess)
            << "seed " << seed << " overlap " << result.overlap_fraction;
        EXPECT_NE(result.status, GlobalRegistrationStatus::kInvalidInput);
    }
}

TEST(GlobalRegistration, TwofoldSymmetricSurfaceIsAmbiguous) {
    std::vector<Bump> bumps = random_bumps(31, 8);
    for (std::size_t i = 0, n = bumps.size(); i < n; ++i) {
        bumps.push_back(
            {-bumps[i].centre_m, bumps[i].height_m, bumps[i].width_m});  // 180° about z.
    }
    const PointCloud target = bumpy_surface(bumps, -0.1, 0.1, 0.001, 0.0);
    const PointCloud source = bumpy_surface(bumps, -0.08, 0.08, 0.001, 0.0005);
    const GlobalRegistrationResult result =
        register_global(transformed(source, random_pose(6, 0.5)), target, {});
    EXPECT_EQ(result.status, GlobalRegistrationStatus::kAmbiguous) << result.message;
}

TEST(GlobalRegistration, AnAxisConstraintPicksOneOfTwoSymmetricPoses) {
    // The surface above is the same turned by 180° about z; a direction known in both
    // frames (here x, as "up" is for a stone on the ground) leaves only the true pose.
    std::vector<Bump> bumps = random_bumps(31, 8);
    for (std::size_t i = 0, n = bumps.size(); i < n; ++i)
        bumps.push_back({-bumps[i].centre_m, bumps[i].height_m, bumps[i].width_m});
    const PointCloud target = bumpy_surface(bumps, -0.1, 0.1, 0.001, 0.0);
    const PointCloud source = bumpy_surface(bumps, -0.08, 0.08, 0.001, 0.0005);
    const Pose moved = random_pose(6, 0.5);
    GlobalRegistrationConfig config;
    config.axis_constraint =
        AxisConstraint{.source_axis = moved.linear() * Eigen::Vector3d::UnitX(),
                       .target_axis = Eigen::Vector3d::UnitX(),
                       .max_angle_deg = 30.0};
    const GlobalRegistrationResult result =
        register_global(transformed(source, moved), target, config);
    ASSERT_EQ(result.status, GlobalRegistrationStatus::kSuccess) << result.message;
    const PoseDifference d = pose_difference(result.T_target_source, moved.inverse());
    EXPECT_LT(d.rotation_deg, 0.5);
    EXPECT_LT(d.translation_m, 0.001);
    for (const HypothesisOutcome& h : result.hypotheses)
        EXPECT_TRUE(config.axis_constraint->admits(h.hypothesis.T_target_source));
}

TEST(AxisConstraint, AdmitsAnglesWithinItsBounds) {
    const AxisConstraint turned{.min_angle_deg = 90.0, .max_angle_deg = 180.0};
    const Pose flip(Eigen::AngleAxisd(std::numbers::pi, Eigen::Vector3d::UnitX()));
    EXPECT_TRUE(turned.admits(flip));
    EXPECT_FALSE(turned.admits(Pose::Identity()));
    const AxisConstraint kept{.max_angle_deg = 30.0};
    EXPECT_TRUE(kept.admits(Pose(Eigen::AngleAxisd(0.4, Eigen::Vector3d::UnitY()))));   // 23°
    EXPECT_FALSE(kept.admits(Pose(Eigen::AngleAxisd(0.6, Eigen::Vector3d::UnitY()))));  // 34°
}

TEST(GlobalRegistration, MissingNormalsOrEmptyCloudsAreInvalidInput) {
    PointCloud cloud = bumpy_surface(random_bumps(3, 5), -0.02, 0.02, 0.002, 0.0);
    EXPECT_EQ(register_global(PointCloud{}, cloud, {}).status,
              GlobalRegistrationStatus::kInvalidInput);
    PointCloud bare = cloud;
    bare.normals.clear();
    const GlobalRegistrationResult result = register_global(bare, cloud, {});
    EXPECT_EQ(result.status, GlobalRegistrationStatus::kInvalidInput);
    EXPECT_FALSE(result.message.empty());
    EXPECT_EQ(to_string(result.status), "invalid_input");
}

TEST(GlobalRegistration, FlatSurfacesFindNoConsensus) {
    const PointCloud plane = bumpy_surface({}, -0.05, 0.05, 0.002, 0.0);
    const GlobalRegistrationResult result = register_global(plane, plane, {});
    EXPECT_NE(result.status, GlobalRegistrationStatus::kSuccess);
}

}  // namespace
}  // namespace anascan
