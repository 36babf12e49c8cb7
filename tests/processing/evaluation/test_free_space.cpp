// check_free_space on two ray-cast views of a box on the ground: the true relative pose
// puts few points in free space, look-alike poses (the box turned by 90° about the vertical,
// or turned over) put many.
#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <numbers>
#include <optional>
#include <random>

#include "anascan/processing/core/point_cloud.hpp"
#include "anascan/processing/core/pose.hpp"
#include "anascan/processing/evaluation/free_space.hpp"

namespace anascan {
namespace {

const Eigen::Vector3d kBoxMin(-0.2, -0.08, 0.0), kBoxMax(0.2, 0.08, 0.12);
constexpr double kGroundHalfWidthM = 0.6;

/// Distance along a unit ray to the box (slab test) or the ground z = 0 in its square.
std::optional<double> cast(const Eigen::Vector3d& eye, const Eigen::Vector3d& ray) {
    double t0 = 0.0, t1 = std::numeric_limits<double>::infinity();
    for (int a = 0; a < 3; ++a) {
        const double ta = (kBoxMin[a] - eye[a]) / ray[a], tb = (kBoxMax[a] - eye[a]) / ray[a];
        t0 = std::max(t0, std::min(ta, tb));
        t1 = std::min(t1, std::max(ta, tb));
    }
    std::optional<double> hit;
    if (t0 <= t1) hit = t0;
    if (ray.z() < 0.0) {
        const double t = -eye.z() / ray.z();
        const Eigen::Vector3d p = eye + t * ray;
        if (std::abs(p.x()) < kGroundHalfWidthM && std::abs(p.y()) < kGroundHalfWidthM &&
            (!hit || t < *hit)) {
            hit = t;
        }
    }
    return hit;
}

/// Sensor at `eye` looking at the box's middle (OpenCV frame: z forward, y down).
Pose sensor_pose(const Eigen::Vector3d& eye) { return look_at(eye, {0.0, 0.0, 0.06}); }

/// A 320×240 pinhole scan (sensor frame, sensor at the origin), 0.2 mm depth noise.
PointCloud scan_from(const Pose& T_world_sensor, std::uint32_t seed) {
    std::mt19937 rng(seed);
    std::normal_distribution<double> noise(0.0, 0.0002);
    PointCloud cloud;
    for (int v = 0; v < 240; ++v) {
        for (int u = 0; u < 320; ++u) {
            const Eigen::Vector3d ray =
                Eigen::Vector3d((u - 160) / 400.0, (v - 120) / 400.0, 1.0).normalized();
            const auto t = cast(T_world_sensor.translation(), T_world_sensor.linear() * ray);
            if (t) cloud.positions.push_back((ray * (*t + noise(rng))).cast<float>());
        }
    }
    return cloud;
}

/// The world turned by `angle_deg` about `axis` through the box centre.
Pose turn(const Eigen::Vector3d& axis, double angle_deg) {
    const Eigen::Vector3d centre = 0.5 * (kBoxMin + kBoxMax);
    return Eigen::Translation3d(centre) *
           Eigen::AngleAxisd(angle_deg * std::numbers::pi / 180.0, axis.normalized()) *
           Eigen::Translation3d(-centre);
}

struct TwoViews {
    Pose T_world_a = sensor_pose({0.9, 0.3, 0.7});
    Pose T_world_b = sensor_pose({0.5, 0.8, 0.75});
    PointCloud a = scan_from(T_world_a, 1);
    PointCloud b = scan_from(T_world_b, 2);

    /// B's points into A's frame, the world turned by `T_turn` in between.
    FreeSpaceResult check(const Pose& T_turn) const {
        return check_free_space(a, Eigen::Vector3d::Zero(), 0.0, b,
                                T_world_a.inverse() * T_turn * T_world_b, {});
    }
};

TEST(FreeSpace, TruePoseLeavesFreeSpaceEmpty) {
    const TwoViews views;
    ASSERT_GT(views.a.size(), 10000u);
    const FreeSpaceResult r = views.check(Pose::Identity());
    ASSERT_TRUE(r.valid);
    std::printf("violation fraction at the true pose: %.4f\n", r.violation_fraction);
    EXPECT_GT(r.in_view, r.samples / 2);  // Both see most of the ground and the box.
    EXPECT_LT(r.violation_fraction, 0.01);
    EXPECT_LE(r.violation_fraction, FreeSpaceConfig{}.max_violation_fraction);
}

TEST(FreeSpace, TurnedPosesPutPointsInFreeSpace) {
    const TwoViews views;
    const FreeSpaceResult quarter = views.check(turn(Eigen::Vector3d::UnitZ(), 90.0));
    const FreeSpaceResult over = views.check(turn(Eigen::Vector3d::UnitX(), 180.0));
    ASSERT_TRUE(quarter.valid);
    ASSERT_TRUE(over.valid);
    std::printf("violation fraction: turned 90 deg %.4f, turned over %.4f\n",
                quarter.violation_fraction, over.violation_fraction);
    // Only the box can violate: the ground of one view lies on the other's.
    EXPECT_GT(quarter.violation_fraction, 1.5 * FreeSpaceConfig{}.max_violation_fraction);
    EXPECT_GT(over.violation_fraction, 2.0 * FreeSpaceConfig{}.max_violation_fraction);
    EXPECT_GT(quarter.violation_fraction, 5.0 * views.check(Pose::Identity()).violation_fraction);
}

TEST(FreeSpace, OccludedPointsAreNoViolation) {
    // B's points seen from behind A's surface: the same scan moved 5 cm away from A's sensor
    // is hidden behind A's surface, 5 cm toward it is in free space.
    const TwoViews views;
    Pose away = Pose::Identity(), toward = Pose::Identity();
    away.translation() = Eigen::Vector3d(0, 0, 0.05);
    toward.translation() = Eigen::Vector3d(0, 0, -0.05);
    const FreeSpaceConfig config;
    const FreeSpaceResult behind =
        check_free_space(views.a, Eigen::Vector3d::Zero(), 0.0, views.a, away, config);
    const FreeSpaceResult in_front =
        check_free_space(views.a, Eigen::Vector3d::Zero(), 0.0, views.a, toward, config);
    EXPECT_LT(behind.violation_fraction, 0.01);
    EXPECT_GT(in_front.violation_fraction, 0.9);
}

TEST(FreeSpace, EmptyCloudsGiveNoResult) {
    const TwoViews views;
    EXPECT_FALSE(
        check_free_space(PointCloud{}, Eigen::Vector3d::Zero(), 0.0, views.b, Pose::Identity(), {})
            .valid);
    EXPECT_FALSE(
        check_free_space(views.a, Eigen::Vector3d::Zero(), 0.0, PointCloud{}, Pose::Identity(), {})
            .valid);
}

}  // namespace
}  // namespace anascan
