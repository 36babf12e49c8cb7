// orient_as_range_scan: the side a single range scan was seen from, in unknown frames.
#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <cmath>
#include <random>

#include "anascan/processing/cleaning/normals.hpp"
#include "anascan/processing/cleaning/view_side.hpp"
#include "anascan/processing/core/pose.hpp"
#include "anascan/processing/evaluation/pose_sampling.hpp"

namespace anascan {
namespace {

/// A range scan of a sphere of radius 0.1 m seen from +z: the cap within `cap_deg` of the
/// pole, points on a jittered grid, normals estimated (signs arbitrary).
PointCloud sphere_cap(double cap_deg, std::mt19937& rng) {
    std::uniform_real_distribution<double> jitter(-0.3, 0.3);
    PointCloud cloud;
    const double radius = 0.1, step = 0.002;
    const double extent = radius * std::sin(cap_deg * M_PI / 180.0);
    for (double x = -extent; x <= extent; x += step) {
        for (double y = -extent; y <= extent; y += step) {
            const double px = x + jitter(rng) * step, py = y + jitter(rng) * step;
            if (px * px + py * py > extent * extent) continue;
            const double z = std::sqrt(radius * radius - px * px - py * py);
            cloud.positions.emplace_back(float(px), float(py), float(z));
        }
    }
    estimate_normals(cloud, {});
    return cloud;
}

/// Fraction of normals facing the sensor at `sensor_m` (cloud frame).
double facing_sensor(const PointCloud& cloud, const Eigen::Vector3f& sensor_m) {
    std::size_t facing = 0;
    for (std::size_t i = 0; i < cloud.size(); ++i) {
        facing += cloud.normals[i].dot(sensor_m - cloud.positions[i]) > 0.0f;
    }
    return double(facing) / double(cloud.size());
}

TEST(ViewSide, OrientsARangeScanTowardItsSensorInAnyFrame) {
    std::mt19937 rng(3);
    for (int trial = 0; trial < 8; ++trial) {
        PointCloud scan = sphere_cap(40.0 + 5.0 * trial, rng);
        const Pose T = sample_random_pose(rng, 0.5);
        scan = transformed(scan, T);
        std::bernoulli_distribution flip(0.5);
        for (Eigen::Vector3f& n : scan.normals) n = flip(rng) ? -n : n;
        const ViewSideResult side = orient_as_range_scan(scan);
        ASSERT_TRUE(side.oriented);
        EXPECT_TRUE(side.decided);
        EXPECT_GT(side.convexity, 0.0);
        EXPECT_GT(side.facing_fraction, 0.9);
        const Eigen::Vector3f sensor_m = (T * Eigen::Vector3d(0.0, 0.0, 1.0)).cast<float>();
        EXPECT_GT(facing_sensor(scan, sensor_m - scan.origin_m.cast<float>()), 0.99) << trial;
        const Eigen::Vector3d view = T.linear().col(2);
        EXPECT_GT(side.view_direction.cast<double>().dot(view), 0.95) << trial;
    }
}

TEST(ViewSide, FlatScanIsUndecidedAndFacesLocalZ) {
    PointCloud plane;
    for (int i = 0; i < 40; ++i)
        for (int j = 0; j < 40; ++j) plane.positions.emplace_back(0.002f * i, 0.002f * j, 0.0f);
    plane.normals.assign(plane.size(), Eigen::Vector3f(0.0f, 0.0f, -1.0f));
    const ViewSideResult side = orient_as_range_scan(plane);
    EXPECT_FALSE(side.decided);
    EXPECT_GT(plane.normals.front().z(), 0.0f);
}

TEST(ViewSide, NoNormalsIsReportedNotOriented) {
    PointCloud cloud;
    cloud.positions.emplace_back(0.0f, 0.0f, 0.0f);
    EXPECT_FALSE(orient_as_range_scan(cloud).oriented);
    cloud.normals.emplace_back(Eigen::Vector3f::Zero());
    EXPECT_FALSE(orient_as_range_scan(cloud).oriented);
}

}  // namespace
}  // namespace anascan
