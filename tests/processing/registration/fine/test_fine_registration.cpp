// Fine registration on analytic shapes with known transforms, applied forward and inverse
// from several perturbations (small_gicp style): a non-symmetric height field converges to
// the truth; a plane and a cylinder report the directions they cannot fix; no overlap and
// bad input report their status; results do not depend on the number of threads.
#include <gtest/gtest.h>
#include <tbb/global_control.h>

#include <Eigen/Geometry>
#include <cmath>
#include <limits>
#include <numbers>
#include <vector>

#include "anascan/processing/core/pose.hpp"
#include "anascan/processing/registration/fine/fine_registration.hpp"
#include "anascan/processing/spatial/kdtree.hpp"

namespace anascan {
namespace {

constexpr double kPi = std::numbers::pi;

double deg(double d) { return d * kPi / 180.0; }

// z = h(x, y): a sum of sinusoids without symmetry, sampled every `spacing_m` on a
// 0.2 m × 0.2 m square, with analytic unit normals (+z side).
PointCloud height_field(double spacing_m = 0.001) {
    PointCloud cloud;
    const int n = static_cast<int>(0.2 / spacing_m);
    for (int i = 0; i < n; ++i) {
        for (int j = 0; j < n; ++j) {
            const double x = -0.1 + i * spacing_m;
            const double y = -0.1 + j * spacing_m;
            const double z = 0.010 * std::sin(40 * x) + 0.008 * std::cos(55 * y + 0.3) +
                             0.005 * std::sin(30 * (x + 0.7 * y));
            const double zx = 0.4 * std::cos(40 * x) + 0.15 * std::cos(30 * (x + 0.7 * y));
            const double zy = -0.44 * std::sin(55 * y + 0.3) + 0.105 * std::cos(30 * (x + 0.7 * y));
            cloud.positions.emplace_back(x, y, z);
            cloud.normals.push_back(Eigen::Vector3d(-zx, -zy, 1.0).normalized().cast<float>());
        }
    }
    return cloud;
}

// The plane z = 0 on a 0.2 m square, normals +z.
PointCloud plane() {
    PointCloud cloud;
    for (int i = 0; i < 200; ++i) {
        for (int j = 0; j < 200; ++j) {
            cloud.positions.emplace_back(-0.1f + 0.001f * i, -0.1f + 0.001f * j, 0.0f);
            cloud.normals.emplace_back(0.0f, 0.0f, 1.0f);
        }
    }
    return cloud;
}

// A full cylinder of radius 5 cm about the y axis, 0.2 m long, outward normals.
PointCloud cylinder() {
    PointCloud cloud;
    for (int i = 0; i < 314; ++i) {
        const double a = 2.0 * kPi * i / 314.0;
        for (int j = 0; j < 200; ++j) {
            cloud.positions.emplace_back(0.05 * std::cos(a), -0.1 + 0.001 * j, 0.05 * std::sin(a));
            cloud.normals.emplace_back(std::cos(a), 0.0, std::sin(a));
        }
    }
    return cloud;
}

Pose make_transform(const Eigen::Vector3d& axis, double angle_rad, const Eigen::Vector3d& t_m) {
    Pose T = Pose::Identity();
    T.linear() = Eigen::AngleAxisd(angle_rad, axis.normalized()).matrix();
    T.translation() = t_m;
    return T;
}

// Perturbations of the initial guess: 3° and 3 mm in several directions.
std::vector<Pose> perturbations() {
    return {make_transform({1, 0, 0}, deg(3), {0.003, 0, 0}),
            make_transform({0, 1, 0}, deg(-3), {0, -0.003, 0.001}),
            make_transform({0, 0, 1}, deg(3), {-0.002, 0.002, -0.001}),
            make_transform({1, -1, 2}, deg(2.5), {0.001, 0.001, 0.0025})};
}

FineRegistrationConfig exact_config() {
    return {.max_correspondence_distance_m = 0.012,
            .rotation_tolerance_rad = 1e-9,
            .translation_tolerance_m = 1e-10};
}

void expect_pose_within(const Pose& estimate, const Pose& truth, double max_deg, double max_m) {
    const PoseDifference d = pose_difference(truth, estimate);
    EXPECT_LT(d.rotation_deg, max_deg);
    EXPECT_LT(d.translation_m, max_m);
}

// The truth T_target_source; the source is the target moved by its inverse.
const Pose kTruth = make_transform({0.3, -0.5, 0.8}, deg(20), {0.05, -0.02, 0.03});

TEST(FineRegistration, HeightFieldConvergesToTruthForward) {
    const PointCloud target = height_field();
    const PointCloud source = transformed(target, kTruth.inverse());
    for (const Pose& delta : perturbations()) {
        const FineRegistrationResult r =
            register_fine(source, target, kTruth * delta, exact_config());
        ASSERT_EQ(r.status, FineRegistrationStatus::kConverged) << r.message;
        expect_pose_within(r.T_target_source, kTruth, 1e-4, 1e-6);
        EXPECT_LT(r.rms_m, 1e-6);
        EXPECT_GT(r.overlap_fraction, 0.99);
        ASSERT_TRUE(r.normal_deviation_deg.has_value());
        EXPECT_LT(*r.normal_deviation_deg, 1e-3);
        EXPECT_GT(r.degeneracy.eigenvalue_ratio, 1e-3);
        EXPECT_LE(r.iterations, 15);
    }
}

TEST(FineRegistration, HeightFieldConvergesToTruthInverse) {
    const PointCloud target = height_field();
    const PointCloud source = transformed(target, kTruth.inverse());
    for (const Pose& delta : perturbations()) {
        const Pose initial = (kTruth * delta).inverse();  // target -> source now.
        const FineRegistrationResult r = register_fine(target, source, initial, exact_config());
        ASSERT_EQ(r.status, FineRegistrationStatus::kConverged) << r.message;
        expect_pose_within(r.T_target_source, kTruth.inverse(), 1e-4, 1e-6);
    }
}

TEST(FineRegistration, LargeOriginsKeepPrecision) {
    PointCloud target = height_field();
    const Eigen::Vector3d site(512000.0, 5300000.0, 250.0);  // UTM-like site frame.
    target.origin_m = site;
    // The same motions as elsewhere, but about the site point instead of the UTM origin.
    const Pose to_site(Eigen::Translation3d{site});
    const Pose truth = to_site * kTruth * to_site.inverse();
    PointCloud source = transformed(target, truth.inverse());
    source.origin_m += Eigen::Vector3d(3.0, -4.0, 1.0);
    for (auto& p : source.positions) p -= Eigen::Vector3f(3.0f, -4.0f, 1.0f);
    const Pose initial = to_site * kTruth * perturbations()[1] * to_site.inverse();
    const FineRegistrationResult r = register_fine(source, target, initial, exact_config());
    ASSERT_EQ(r.status, FineRegistrationStatus::kConverged) << r.message;
    // Compared about the site point (a 1e-9 rad error moves the UTM origin by metres).
    expect_pose_within(to_site.inverse() * r.T_target_source * to_site, kTruth, 1e-4, 1e-6);
}

TEST(FineRegistration, EveryKernelConverges) {
    const PointCloud target = height_field();
    const PointCloud source = transformed(target, kTruth.inverse());
    for (RobustKernel kernel : {RobustKernel::kNone, RobustKernel::kHuber, RobustKernel::kTukey}) {
        FineRegistrationConfig config = exact_config();
        config.robust_kernel = kernel;
        config.robust_width_fraction = 0.3;
        const FineRegistrationResult r =
            register_fine(source, target, kTruth * perturbations()[3], config);
        EXPECT_EQ(r.status, FineRegistrationStatus::kConverged) << r.message;
        expect_pose_within(r.T_target_source, kTruth, 1e-4, 1e-6);
    }
}

TEST(FineRegistration, PrebuiltTreeGivesTheSameResult) {
    const PointCloud target = height_field();
    const PointCloud source = transformed(target, kTruth.inverse());
    const KdTree tree(target.positions);
    const Pose initial = kTruth * perturbations()[0];
    const FineRegistrationResult a = register_fine(source, target, initial, {});
    const FineRegistrationResult b = register_fine(source, target, tree, initial, {});
    EXPECT_EQ(a.T_target_source.matrix(), b.T_target_source.matrix());
    EXPECT_EQ(a.iterations, b.iterations);
}

TEST(FineRegistration, SameResultWithOneAndTwoThreads) {
    const PointCloud target = height_field();
    const PointCloud source = transformed(target, kTruth.inverse());
    const Pose initial = kTruth * perturbations()[2];
    const auto run = [&](std::size_t threads) {
        const tbb::global_control limit(tbb::global_control::max_allowed_parallelism, threads);
        return register_fine(source, target, initial, {.chunk_size = 64});
    };
    const FineRegistrationResult one = run(1);
    const FineRegistrationResult two = run(2);
    EXPECT_EQ(one.T_target_source.matrix(), two.T_target_source.matrix());
    EXPECT_EQ(one.iterations, two.iterations);
    EXPECT_EQ(one.rms_m, two.rms_m);
    EXPECT_EQ(one.degeneracy.eigenvalue_ratio, two.degeneracy.eigenvalue_ratio);
}

TEST(FineRegistration, KeepsFinalCorrespondencesOnlyWhenAsked) {
    const PointCloud target = height_field();
    const PointCloud source = transformed(target, kTruth.inverse());
    const Pose initial = kTruth * perturbations()[0];
    EXPECT_TRUE(register_fine(source, target, initial, {}).correspondences.empty());
    const FineRegistrationResult r =
        register_fine(source, target, initial, {.keep_correspondences = true});
    ASSERT_EQ(r.correspondences.size(), r.inlier_count);
    ASSERT_GT(r.inlier_count, 1000u);
    for (const FineCorrespondence& c : r.correspondences) {
        const double residual = (r.T_target_source * c.source_point_m - c.target_point_m)
                                    .dot(c.target_normal.cast<double>());
        EXPECT_NEAR(residual, c.residual_m, 1e-6);
    }
}

TEST(FineRegistration, TargetWithSomeNanPointsStillConverges) {
    PointCloud target = height_field();
    const PointCloud source = transformed(target, kTruth.inverse());
    const float nan = std::numeric_limits<float>::quiet_NaN();
    for (std::size_t i = 0; i < target.size(); i += 7) target.positions[i].x() = nan;
    for (std::size_t i = 3; i < target.size(); i += 11) target.normals[i].z() = nan;
    const FineRegistrationResult r = register_fine(source, target, kTruth * perturbations()[0], {});
    EXPECT_EQ(r.status, FineRegistrationStatus::kConverged) << r.message;
    expect_pose_within(r.T_target_source, kTruth, 1e-3, 1e-5);
}

// A plane fixes only the offset along its normal and the two tilts; the constraint slides
// in the plane and turns about the normal.
TEST(FineRegistration, PlaneReportsDegenerateAndStillFixesOffsetAndTilt) {
    const PointCloud target = plane();
    const Pose truth = make_transform({1, 1, 0}, deg(2), {0.004, -0.003, 0.002});
    const PointCloud source = transformed(target, truth.inverse());
    const FineRegistrationResult r = register_fine(source, target, Pose::Identity(), {});
    EXPECT_EQ(r.status, FineRegistrationStatus::kDegenerate);
    EXPECT_FALSE(r.message.empty());
    EXPECT_LT(r.degeneracy.eigenvalue_ratio, 1e-6);
    // Weak space: rotation about z (index 2) and translation in x, y (indices 3, 4).
    const auto& w = r.degeneracy.weakest_direction;
    EXPECT_NEAR(Eigen::Vector3d(w(2), w(3), w(4)).norm(), 1.0, 1e-6);
    // The moved source lies in the plane: normal offset and tilt fixed.
    const Eigen::Vector3d n = r.T_target_source.linear() * source.normals[0].cast<double>();
    EXPECT_GT(n.z(), std::cos(deg(1e-3)));
    EXPECT_LT(std::abs((r.T_target_source * source.world_position(0)).z()), 1e-6);
}

TEST(FineRegistration, CylinderReportsDegenerateAlongItsAxis) {
    const PointCloud target = cylinder();
    const Pose truth = make_transform({0, 0, 1}, deg(2), {0.002, 0.003, -0.001});
    const PointCloud source = transformed(target, truth.inverse());
    const FineRegistrationResult r = register_fine(source, target, Pose::Identity(), {});
    EXPECT_EQ(r.status, FineRegistrationStatus::kDegenerate) << r.message;
    EXPECT_LT(r.degeneracy.eigenvalue_ratio, 1e-6);
    // Weak space: rotation about the y axis (index 1) and translation along it (index 4).
    const auto& w = r.degeneracy.weakest_direction;
    EXPECT_NEAR(Eigen::Vector2d(w(1), w(4)).norm(), 1.0, 1e-6);
    // The fixed directions are right: the moved source lies on the cylinder.
    for (std::size_t i = 0; i < source.size(); i += 997) {
        const Eigen::Vector3d p = r.T_target_source * source.world_position(i);
        EXPECT_NEAR(std::hypot(p.x(), p.z()), 0.05, 1e-6);
    }
}

TEST(FineRegistration, NoOverlapReportsInsufficientOverlap) {
    const PointCloud target = height_field();
    const PointCloud source = transformed(target, make_transform({0, 0, 1}, 0, {1.0, 0, 0}));
    const FineRegistrationResult r = register_fine(source, target, Pose::Identity(), {});
    EXPECT_EQ(r.status, FineRegistrationStatus::kInsufficientOverlap);
    EXPECT_FALSE(r.message.empty());
}

TEST(FineRegistration, SmallOverlapReportsInsufficientOverlap) {
    const PointCloud target = height_field();
    // Only a 2 cm strip of the 20 cm square overlaps.
    const PointCloud source = transformed(target, make_transform({0, 0, 1}, 0, {0.18, 0, 0}));
    const FineRegistrationResult r =
        register_fine(source, target, Pose::Identity(), {.min_overlap_fraction = 0.2});
    EXPECT_EQ(r.status, FineRegistrationStatus::kInsufficientOverlap);
    EXPECT_LT(r.overlap_fraction, 0.2);
}

struct InvalidCase {
    const char* name;
    PointCloud source;
    PointCloud target;
    Pose initial = Pose::Identity();
    FineRegistrationConfig config;
};

TEST(FineRegistration, InvalidInputReportsStatusWithMessageAndKeepsInitialPose) {
    const PointCloud good = height_field(0.004);
    const float nan = std::numeric_limits<float>::quiet_NaN();
    PointCloud no_normals = good;
    no_normals.normals.clear();
    PointCloud all_nan = good;
    for (auto& n : all_nan.normals) n.setConstant(nan);
    PointCloud nan_source = good;
    for (auto& p : nan_source.positions) p.setConstant(nan);
    PointCloud inconsistent = good;
    inconsistent.normals.pop_back();
    Pose nan_pose = Pose::Identity();
    nan_pose.translation().x() = std::numeric_limits<double>::quiet_NaN();
    std::vector<InvalidCase> cases{
        {"empty source", {}, good, Pose::Identity(), {}},
        {"empty target", good, {}, Pose::Identity(), {}},
        {"target without normals", good, no_normals, Pose::Identity(), {}},
        {"target normals all NaN", good, all_nan, Pose::Identity(), {}},
        {"source all NaN", nan_source, good, Pose::Identity(), {}},
        {"inconsistent target", good, inconsistent, Pose::Identity(), {}},
        {"NaN initial pose", good, good, nan_pose, {}},
        {"bad config", good, good, Pose::Identity(), {.max_iterations = 0}},
        {"zero gate", good, good, Pose::Identity(), {.max_correspondence_distance_m = 0.0}},
    };
    const Pose initial = make_transform({0, 1, 0}, 0.1, {0.1, 0.2, 0.3});
    for (InvalidCase& c : cases) {
        const Pose start = c.name == std::string("NaN initial pose") ? c.initial : initial;
        const FineRegistrationResult r = register_fine(c.source, c.target, start, c.config);
        EXPECT_EQ(r.status, FineRegistrationStatus::kInvalidInput) << c.name;
        EXPECT_FALSE(r.message.empty()) << c.name;
        if (start.matrix().allFinite()) {
            EXPECT_EQ(r.T_target_source.matrix(), start.matrix()) << c.name;
        }
    }
}

TEST(FineRegistration, PrebuiltTreeOfAnotherCloudIsInvalid) {
    const PointCloud target = height_field(0.004);
    const PointCloud other = height_field(0.002);
    const KdTree tree(other.positions);
    const FineRegistrationResult r = register_fine(target, target, tree, Pose::Identity(), {});
    EXPECT_EQ(r.status, FineRegistrationStatus::kInvalidInput);
    EXPECT_FALSE(r.message.empty());
}

TEST(FineRegistration, StatusNamesAreStable) {
    EXPECT_EQ(to_string(FineRegistrationStatus::kConverged), "converged");
    EXPECT_EQ(to_string(FineRegistrationStatus::kDegenerate), "degenerate");
    EXPECT_EQ(to_string(FineRegistrationStatus::kInsufficientOverlap), "insufficient_overlap");
    EXPECT_EQ(to_string(FineRegistrationStatus::kInvalidInput), "invalid_input");
    EXPECT_EQ(to_string(FineRegistrationStatus::kMaxIterations), "max_iterations");
}

}  // namespace
}  // namespace anascan
