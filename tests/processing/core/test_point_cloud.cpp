#include <gtest/gtest.h>

#include <limits>

#include "anascan/processing/core/point_cloud.hpp"

namespace anascan {
namespace {

PointCloud three_points() {
    PointCloud cloud;
    cloud.origin_m = {10.0, 20.0, 30.0};
    cloud.positions = {{0, 0, 0}, {1, 0, 0}, {0, 2, 0}};
    cloud.normals = {{0, 0, 1}, {0, 1, 0}, {1, 0, 0}};
    cloud.colors = {{1, 2, 3}, {4, 5, 6}, {7, 8, 9}};
    cloud.intensity = {0.1f, 0.2f, 0.3f};
    return cloud;
}

TEST(PointCloud, ConsistentWhenAttributesEmptyOrFull) {
    PointCloud cloud = three_points();
    EXPECT_TRUE(cloud.attributes_consistent());
    EXPECT_EQ(describe_inconsistency(cloud), "");
    EXPECT_TRUE(PointCloud{}.attributes_consistent());
    EXPECT_TRUE(cloud.has_normals());
    EXPECT_FALSE(cloud.has_confidence());
}

TEST(PointCloud, DescribesEveryInconsistentAttribute) {
    PointCloud cloud = three_points();
    cloud.normals.pop_back();
    cloud.confidence = {0.5f};
    EXPECT_FALSE(cloud.attributes_consistent());
    const std::string text = describe_inconsistency(cloud);
    EXPECT_NE(text.find("normals has 2 entries for 3 points"), std::string::npos) << text;
    EXPECT_NE(text.find("confidence has 1 entries for 3 points"), std::string::npos) << text;
    EXPECT_EQ(text.find("colors"), std::string::npos) << text;
}

TEST(PointCloud, SelectKeepsOrderOriginAndAttributes) {
    const PointCloud cloud = three_points();
    const std::vector<std::size_t> indices{2, 0, 2};
    const PointCloud out = select(cloud, indices);
    ASSERT_EQ(out.size(), 3u);
    EXPECT_EQ(out.origin_m, cloud.origin_m);
    EXPECT_EQ(out.positions[0], cloud.positions[2]);
    EXPECT_EQ(out.positions[1], cloud.positions[0]);
    EXPECT_EQ(out.normals[2], cloud.normals[2]);
    EXPECT_EQ(out.colors[1], cloud.colors[0]);
    EXPECT_FLOAT_EQ(out.intensity[0], 0.3f);
    EXPECT_FALSE(out.has_confidence());
    EXPECT_TRUE(out.attributes_consistent());
    EXPECT_TRUE(select(cloud, {}).empty());
}

TEST(PointCloud, AppendReexpressesPointsInTheFirstOrigin) {
    PointCloud cloud = three_points();
    PointCloud other = three_points();
    other.origin_m = {11.0, 18.0, 30.5};
    append(cloud, other);
    ASSERT_EQ(cloud.size(), 6u);
    EXPECT_EQ(cloud.origin_m, Eigen::Vector3d(10.0, 20.0, 30.0));
    for (std::size_t i = 0; i < other.size(); ++i) {
        EXPECT_TRUE(cloud.world_position(3 + i).isApprox(other.world_position(i), 1e-12));
    }
    EXPECT_TRUE(cloud.attributes_consistent());
    EXPECT_EQ(cloud.normals.size(), 6u);
    EXPECT_EQ(cloud.colors[4], other.colors[1]);
}

TEST(PointCloud, AppendKeepsOnlyAttributesBothHave) {
    PointCloud cloud = three_points();
    PointCloud other = three_points();
    other.normals.clear();
    other.confidence = {1.0f, 1.0f, 1.0f};  // Only `other` has it: cannot survive.
    append(cloud, other);
    EXPECT_FALSE(cloud.has_normals());
    EXPECT_FALSE(cloud.has_confidence());
    EXPECT_TRUE(cloud.has_colors());
    EXPECT_TRUE(cloud.has_intensity());
    EXPECT_TRUE(cloud.attributes_consistent()) << describe_inconsistency(cloud);
}

TEST(PointCloud, AppendToEmptyTakesEverything) {
    PointCloud cloud;
    const PointCloud other = three_points();
    append(cloud, other);
    EXPECT_EQ(cloud.origin_m, other.origin_m);
    EXPECT_EQ(cloud.positions, other.positions);
    EXPECT_EQ(cloud.normals, other.normals);
    EXPECT_EQ(cloud.intensity, other.intensity);
    EXPECT_TRUE(cloud.attributes_consistent());
}

TEST(PointCloud, RemoveNonFiniteDropsPointsAndTheirAttributes) {
    PointCloud cloud = three_points();
    cloud.positions[1].y() = std::numeric_limits<float>::quiet_NaN();
    cloud.positions.emplace_back(std::numeric_limits<float>::infinity(), 0.0f, 0.0f);
    cloud.normals.emplace_back(0, 0, 1);
    cloud.colors.push_back({});
    cloud.intensity.push_back(9.0f);
    EXPECT_EQ(remove_non_finite(cloud), 2u);
    ASSERT_EQ(cloud.size(), 2u);
    EXPECT_TRUE(cloud.attributes_consistent());
    EXPECT_EQ(cloud.positions[1], Eigen::Vector3f(0, 2, 0));
    EXPECT_EQ(cloud.colors[1], (Rgb8{7, 8, 9}));
    EXPECT_FLOAT_EQ(cloud.intensity[0], 0.1f);
    EXPECT_EQ(remove_non_finite(cloud), 0u);
}

TEST(PointCloud, LocalBounds) {
    PointCloud cloud = three_points();
    cloud.positions.emplace_back(-1.0f, 0.5f, -3.0f);
    const Bounds b = local_bounds(cloud);
    EXPECT_EQ(b.min, Eigen::Vector3f(-1.0f, 0.0f, -3.0f));
    EXPECT_EQ(b.max, Eigen::Vector3f(1.0f, 2.0f, 0.0f));
    EXPECT_EQ(b.extent(), Eigen::Vector3f(2.0f, 2.0f, 3.0f));
    const Bounds empty = local_bounds(PointCloud{});
    EXPECT_EQ(empty.min, Eigen::Vector3f::Zero());
    EXPECT_EQ(empty.max, Eigen::Vector3f::Zero());
}

TEST(PointCloud, ReserveKeepsAttributesEmpty) {
    PointCloud cloud;
    cloud.reserve(100);
    EXPECT_GE(cloud.positions.capacity(), 100u);
    EXPECT_TRUE(cloud.normals.empty());
    EXPECT_TRUE(cloud.attributes_consistent());
}

}  // namespace
}  // namespace anascan
