#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <numeric>
#include <random>
#include <set>
#include <tuple>

#include "anascan/processing/spatial/voxel_grid.hpp"

namespace anascan {
namespace {

constexpr float kNaN = std::numeric_limits<float>::quiet_NaN();

// Two voxels of 1 m: three points in [0,1)^3 and two in [1,2)x[0,1)x[0,1).
PointCloud two_voxel_cloud() {
    PointCloud cloud;
    cloud.origin_m = {100.0, 200.0, 300.0};
    cloud.positions = {{1.2f, 0.5f, 0.5f},
                       {0.1f, 0.2f, 0.3f},
                       {0.4f, 0.5f, 0.6f},
                       {1.6f, 0.5f, 0.5f},
                       {0.7f, 0.8f, 0.9f}};
    cloud.normals = {{1, 0, 0}, {0, 0, 1}, {0, 1, 0}, {0, 1, 0}, {1, 0, 0}};
    cloud.colors = {{10, 20, 30}, {0, 0, 0}, {30, 60, 90}, {20, 40, 50}, {60, 120, 180}};
    cloud.intensity = {2.0f, 1.0f, 2.0f, 4.0f, 3.0f};
    cloud.confidence = {0.5f, 0.2f, 0.4f, 1.0f, 0.6f};
    return cloud;
}

TEST(VoxelDownsample, MeansOfKnownVoxels) {
    const PointCloud out = voxel_downsample(two_voxel_cloud(), {.voxel_size_m = 1.0});
    ASSERT_EQ(out.size(), 2u);
    ASSERT_TRUE(out.attributes_consistent()) << describe_inconsistency(out);
    EXPECT_EQ(out.origin_m, Eigen::Vector3d(100.0, 200.0, 300.0));
    // Voxel (0,0,0) comes first in key order.
    EXPECT_TRUE(out.positions[0].isApprox(Eigen::Vector3f(0.4f, 0.5f, 0.6f), 1e-6f));
    EXPECT_TRUE(out.positions[1].isApprox(Eigen::Vector3f(1.4f, 0.5f, 0.5f), 1e-6f));
    const float third = 1.0f / std::sqrt(3.0f);
    EXPECT_TRUE(out.normals[0].isApprox(Eigen::Vector3f(third, third, third), 1e-6f));
    EXPECT_TRUE(out.normals[1].isApprox(Eigen::Vector3f(1, 1, 0).normalized(), 1e-6f));
    EXPECT_EQ(out.colors[0], (Rgb8{30, 60, 90}));
    EXPECT_EQ(out.colors[1], (Rgb8{15, 30, 40}));
    EXPECT_FLOAT_EQ(out.intensity[0], 2.0f);
    EXPECT_FLOAT_EQ(out.intensity[1], 3.0f);
    EXPECT_FLOAT_EQ(out.confidence[0], 0.4f);
    EXPECT_FLOAT_EQ(out.confidence[1], 0.75f);
}

TEST(VoxelDownsample, NegativeCoordinatesUseFloor) {
    PointCloud cloud;
    cloud.positions = {{-0.25f, 0.25f, 0.25f}, {-0.75f, 0.75f, 0.75f}, {0.25f, 0.25f, 0.25f}};
    const PointCloud out = voxel_downsample(cloud, {.voxel_size_m = 1.0});
    ASSERT_EQ(out.size(), 2u);
    EXPECT_TRUE(out.positions[0].isApprox(Eigen::Vector3f(-0.5f, 0.5f, 0.5f), 1e-6f));
    EXPECT_TRUE(out.positions[1].isApprox(Eigen::Vector3f(0.25f, 0.25f, 0.25f), 1e-6f));
    EXPECT_FALSE(out.has_normals());
    EXPECT_FALSE(out.has_colors());
}

TEST(VoxelDownsample, OutputIsSortedByVoxelCoordinates) {
    PointCloud cloud;
    cloud.positions = {{2.5f, 0.5f, 0.5f},
                       {0.5f, 3.5f, 0.5f},
                       {0.5f, 0.5f, 1.5f},
                       {0.5f, 0.5f, 0.5f},
                       {-3.5f, 9.5f, 0.5f}};
    const PointCloud out = voxel_downsample(cloud, {.voxel_size_m = 1.0});
    ASSERT_EQ(out.size(), 5u);
    for (std::size_t i = 1; i < out.size(); ++i) {
        const Eigen::Vector3f& a = out.positions[i - 1];
        const Eigen::Vector3f& b = out.positions[i];
        EXPECT_TRUE(std::lexicographical_compare(a.data(), a.data() + 3, b.data(), b.data() + 3))
            << "voxel " << i;
    }
}

PointCloud random_cloud(std::size_t n, std::uint32_t seed) {
    std::mt19937 rng(seed);
    std::uniform_real_distribution<float> coord(-0.05f, 0.05f);
    std::uniform_int_distribution<int> byte(0, 255);
    PointCloud cloud;
    cloud.origin_m = {5.0e5, 4.0e6, 120.0};
    for (std::size_t i = 0; i < n; ++i) {
        cloud.positions.emplace_back(coord(rng), coord(rng), coord(rng));
        cloud.normals.push_back(Eigen::Vector3f(coord(rng), coord(rng), 0.05f).normalized());
        cloud.colors.push_back({static_cast<std::uint8_t>(byte(rng)),
                                static_cast<std::uint8_t>(byte(rng)),
                                static_cast<std::uint8_t>(byte(rng))});
        cloud.intensity.push_back(coord(rng) + 1.0f);
    }
    return cloud;
}

TEST(VoxelDownsample, ResultDoesNotDependOnInputOrder) {
    const PointCloud cloud = random_cloud(20000, 11);
    std::vector<std::size_t> order(cloud.size());
    std::iota(order.begin(), order.end(), 0);
    std::shuffle(order.begin(), order.end(), std::mt19937(12));
    const PointCloud shuffled = select(cloud, order);

    const VoxelDownsampleConfig config{.voxel_size_m = 0.01};
    const PointCloud a = voxel_downsample(cloud, config);
    const PointCloud b = voxel_downsample(shuffled, config);
    ASSERT_EQ(a.size(), b.size());
    EXPECT_LT(a.size(), cloud.size());
    EXPECT_EQ(a.positions, b.positions);
    EXPECT_EQ(a.normals, b.normals);
    EXPECT_EQ(a.colors, b.colors);
    EXPECT_EQ(a.intensity, b.intensity);
    for (const Eigen::Vector3f& n : a.normals) EXPECT_NEAR(n.norm(), 1.0f, 1e-5f);
}

TEST(VoxelDownsample, NonFinitePointsAreDropped) {
    PointCloud cloud;
    cloud.positions = {
        {0.5f, 0.5f, 0.5f}, {kNaN, 0.5f, 0.5f}, {0.5f, INFINITY, 0.5f}, {0.7f, 0.7f, 0.7f}};
    cloud.intensity = {1.0f, 100.0f, 100.0f, 3.0f};
    const PointCloud out = voxel_downsample(cloud, {.voxel_size_m = 1.0});
    ASSERT_EQ(out.size(), 1u);
    EXPECT_TRUE(out.positions[0].isApprox(Eigen::Vector3f(0.6f, 0.6f, 0.6f), 1e-6f));
    EXPECT_FLOAT_EQ(out.intensity[0], 2.0f);

    PointCloud only_nan;
    only_nan.positions = {{kNaN, kNaN, kNaN}};
    EXPECT_TRUE(voxel_downsample(only_nan, {.voxel_size_m = 1.0}).empty());
}

TEST(VoxelDownsample, NonPositiveSizeReturnsCopy) {
    const PointCloud cloud = two_voxel_cloud();
    for (double size : {0.0, -1.0}) {
        const PointCloud out = voxel_downsample(cloud, {.voxel_size_m = size});
        EXPECT_EQ(out.origin_m, cloud.origin_m);
        EXPECT_EQ(out.positions, cloud.positions);
        EXPECT_EQ(out.colors, cloud.colors);
    }
}

TEST(VoxelDownsample, EmptyCloudGivesEmptyCloud) {
    EXPECT_TRUE(voxel_downsample(PointCloud{}, {}).empty());
}

TEST(VoxelDownsample, HugeExtentStillGroupsCorrectly) {
    // 1e-6 m voxels over 2e6 m span more than 2^64 voxels: the fallback path.
    PointCloud cloud;
    cloud.positions = {{1.0e6f, 0, 0}, {-1.0e6f, 0, 0}, {0, 1.0e6f, -1.0e6f}, {1.0e6f, 0, 0}};
    const PointCloud out = voxel_downsample(cloud, {.voxel_size_m = 1e-6});
    ASSERT_EQ(out.size(), 3u);
    EXPECT_EQ(out.positions[0], Eigen::Vector3f(-1.0e6f, 0, 0));
    EXPECT_EQ(out.positions[1], Eigen::Vector3f(0, 1.0e6f, -1.0e6f));
    EXPECT_EQ(out.positions[2], Eigen::Vector3f(1.0e6f, 0, 0));
}

TEST(VoxelDownsample, MillionPointsMatchABruteForceVoxelCount) {
    // Large input takes the radix-sort path; a set of voxel coordinates is the oracle.
    // (Speed is measured in benchmarks, not here.)
    std::mt19937 rng(3);
    std::uniform_real_distribution<float> coord(0.0f, 1.0f);
    PointCloud cloud;
    cloud.positions.resize(1'000'000);
    for (Eigen::Vector3f& p : cloud.positions) p = {coord(rng), coord(rng), coord(rng)};
    std::set<std::tuple<long, long, long>> voxels;
    for (const Eigen::Vector3f& p : cloud.positions) {
        const Eigen::Vector3d v = (p.cast<double>() * (1.0 / 0.002)).array().floor();
        voxels.emplace(static_cast<long>(v.x()), static_cast<long>(v.y()),
                       static_cast<long>(v.z()));
    }
    const PointCloud out = voxel_downsample(cloud, {.voxel_size_m = 0.002});
    EXPECT_EQ(out.size(), voxels.size());
}

}  // namespace
}  // namespace anascan
