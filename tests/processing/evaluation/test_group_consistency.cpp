// check_group_consistency on ray-cast views of a block's corner (stone only, as live
// registration reduces them): the true poses agree; a view turned 30° about the normal of
// its largest face (the top, so it still lies flat on it) is caught by the other faces it
// sees and is the one taken out; a view tilted 35° across faces is caught by its crossing
// normals alone when no sensor position is known.
#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <numbers>
#include <optional>
#include <random>
#include <vector>

#include "anascan/processing/cleaning/normals.hpp"
#include "anascan/processing/core/point_cloud.hpp"
#include "anascan/processing/core/pose.hpp"
#include "anascan/processing/evaluation/group_consistency.hpp"
#include "anascan/processing/spatial/voxel_grid.hpp"

namespace anascan {
namespace {

const Eigen::Vector3d kBoxMin(-0.25, -0.15, 0.0), kBoxMax(0.25, 0.15, 0.25);
const Eigen::Vector3d kTopCentre(0.0, 0.0, 0.25);

/// Distance along a unit ray to the box (slab test).
std::optional<double> cast(const Eigen::Vector3d& eye, const Eigen::Vector3d& ray) {
    double t0 = 0.0, t1 = std::numeric_limits<double>::infinity();
    for (int a = 0; a < 3; ++a) {
        const double ta = (kBoxMin[a] - eye[a]) / ray[a], tb = (kBoxMax[a] - eye[a]) / ray[a];
        t0 = std::max(t0, std::min(ta, tb));
        t1 = std::min(t1, std::max(ta, tb));
    }
    if (t0 <= t1) return t0;
    return std::nullopt;
}

/// A 320×240 pinhole scan of the box from `eye` (sensor frame), 0.2 mm depth noise, reduced
/// to a 3 mm voxel with normals toward the sensor (as live registration keeps scans).
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
    PointCloud reduced = voxel_downsample(cloud, {.voxel_size_m = 0.003});
    estimate_normals(reduced, {});
    orient_toward(reduced, Eigen::Vector3f::Zero());
    return reduced;
}

/// Views of the corner at +x +y, top, from 0.9 m at azimuths 10-80° and 35-45° elevation.
struct CornerViews {
    std::vector<Pose> T_world_scan;
    std::vector<PointCloud> clouds;
    CornerViews() {
        const double deg = std::numbers::pi / 180.0;
        const double azimuths[] = {10.0, 32.0, 55.0, 80.0}, elevations[] = {40.0, 35.0, 45.0, 38.0};
        for (int i = 0; i < 4; ++i) {
            const double az = azimuths[i] * deg, el = elevations[i] * deg;
            const Eigen::Vector3d eye =
                0.9 * Eigen::Vector3d(std::cos(el) * std::cos(az), std::cos(el) * std::sin(az),
                                      std::sin(el)) +
                Eigen::Vector3d(0.0, 0.0, 0.12);
            T_world_scan.push_back(look_at(eye, {0.1, 0.05, 0.15}));
            clouds.push_back(scan_from(T_world_scan.back(), 10u + static_cast<unsigned>(i)));
        }
    }
    /// The group with scan `moved` placed by `T_wrong` applied after its true pose.
    std::vector<ConsistencyScan> group(std::size_t moved, const Pose& T_wrong, bool sensors) const {
        std::vector<ConsistencyScan> scans;
        for (std::size_t i = 0; i < clouds.size(); ++i) {
            ConsistencyScan s{.cloud = &clouds[i], .T_group_scan = T_world_scan[i]};
            if (i == moved) s.T_group_scan = T_wrong * s.T_group_scan;
            if (sensors) s.sensor_origin_scan_m = Eigen::Vector3d::Zero();
            scans.push_back(s);
        }
        return scans;
    }
};

Pose turn_about(const Eigen::Vector3d& point, const Eigen::Vector3d& axis, double deg) {
    return Eigen::Translation3d(point) *
           Eigen::AngleAxisd(deg * std::numbers::pi / 180.0, axis.normalized()) *
           Eigen::Translation3d(-point);
}

void print(const GroupConsistency& g) {
    for (const PairConsistency& p : g.pairs)
        std::printf(
            "pair %zu-%zu: near %zu, crossing %.3f (> %.1f deg), median %.2f deg, free "
            "%.3f / %.3f, %s\n",
            p.a, p.b, p.near_samples, p.crossing_fraction, p.crossing_angle_deg,
            p.median_normal_angle_deg, p.b_seen_from_a.violation_fraction,
            p.a_seen_from_b.violation_fraction, p.agrees ? "agrees" : p.reason.c_str());
}

TEST(GroupConsistency, TheTruePosesAgree) {
    const CornerViews views;
    for (const bool sensors : {true, false}) {
        const std::vector<ConsistencyScan> scans = views.group(0, Pose::Identity(), sensors);
        const GroupConsistency g = check_group_consistency(scans, {});
        print(g);
        EXPECT_TRUE(g.consistent);
        EXPECT_TRUE(g.take_out.empty());
        EXPECT_EQ(g.pairs.size(), 6u);  // Every pair overlaps.
        for (const PairConsistency& p : g.pairs) {
            EXPECT_GT(p.near_samples, 500u);
            EXPECT_LT(p.median_normal_angle_deg, 3.0);
        }
    }
}

TEST(GroupConsistency, AViewTurnedOnItsLargestFaceIsCaughtByItsOtherFaces) {
    const CornerViews views;
    // Scan 1 sees the top (largest) and both sides; turned 30° about the top's normal
    // through its centre, its top still lies on the others' top.
    const Pose wrong = turn_about(kTopCentre, Eigen::Vector3d::UnitZ(), 30.0);
    const std::vector<ConsistencyScan> scans = views.group(1, wrong, true);
    const GroupConsistency g = check_group_consistency(scans, {});
    print(g);
    EXPECT_FALSE(g.consistent);
    ASSERT_EQ(g.take_out, std::vector<std::size_t>{1});
    EXPECT_TRUE(g.scans[1].taken_out);
    EXPECT_EQ(g.scans[1].disagreeing, g.scans[1].overlapping);
    for (const PairConsistency& p : g.pairs) {
        EXPECT_EQ(p.agrees, p.a != 1 && p.b != 1) << describe(p, {});
        if (p.agrees) continue;
        std::printf("%s\n", describe(p, {}).c_str());
        // The top agrees, the turned sides lie in front of the others' sides.
        EXPECT_GT(std::max(p.b_seen_from_a.violation_fraction, p.a_seen_from_b.violation_fraction),
                  FreeSpaceConfig{}.max_violation_fraction);
    }
}

TEST(GroupConsistency, CrossingNormalsCatchATiltWithoutSensors) {
    const CornerViews views;
    const Pose wrong = turn_about(kTopCentre, Eigen::Vector3d(1.0, -1.0, 0.0), 35.0);
    const GroupConsistency g = check_group_consistency(views.group(2, wrong, false), {});
    print(g);
    EXPECT_FALSE(g.consistent);
    ASSERT_EQ(g.take_out, std::vector<std::size_t>{2});
    for (const PairConsistency& p : g.pairs) {
        EXPECT_FALSE(p.b_seen_from_a.valid);  // No sensor: no free-space test.
        if (p.a == 2 || p.b == 2) {
            EXPECT_FALSE(p.agrees);
            EXPECT_GT(p.median_normal_angle_deg, p.crossing_angle_deg);
        }
    }
}

TEST(GroupConsistency, EmptyAndLoneScansSayNothing) {
    const PointCloud empty;
    const CornerViews views;
    const std::vector<ConsistencyScan> scans = {{.cloud = &empty}, {.cloud = &views.clouds[0]}};
    const GroupConsistency g = check_group_consistency(scans, {});
    EXPECT_TRUE(g.consistent);
    EXPECT_TRUE(g.pairs.empty());
    EXPECT_EQ(g.scans.size(), 2u);
}

}  // namespace
}  // namespace anascan
