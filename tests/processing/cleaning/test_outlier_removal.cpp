// Statistical and radius outlier removal on a sampled plane with injected far outliers.

#include <gtest/gtest.h>

#include <algorithm>
#include <random>

#include "anascan/processing/cleaning/outlier_removal.hpp"

namespace anascan {
namespace {

constexpr std::size_t kSurfacePoints = 40000;

// A 0.2 m square of the plane z = 0 (random samples, ~0.001 m apart, 0.1 mm noise), then
// `outliers` points scattered in a 2 m box around it, at least 0.05 m off the plane.
PointCloud noisy_plane_with_outliers(std::size_t outliers, std::uint64_t seed) {
    std::mt19937_64 rng(seed);
    std::uniform_real_distribution<float> in_square(0.0f, 0.2f);
    std::normal_distribution<float> noise(0.0f, 0.0001f);
    std::uniform_real_distribution<float> in_box(-1.0f, 1.0f);
    PointCloud cloud;
    for (std::size_t i = 0; i < kSurfacePoints; ++i) {
        cloud.positions.emplace_back(in_square(rng), in_square(rng), noise(rng));
    }
    while (cloud.size() < kSurfacePoints + outliers) {
        const Eigen::Vector3f p(in_box(rng), in_box(rng), in_box(rng));
        if (std::abs(p.z()) > 0.05f) cloud.positions.push_back(p);
    }
    return cloud;
}

std::size_t count_below(const std::vector<std::size_t>& kept, std::size_t limit) {
    return std::size_t(std::count_if(kept.begin(), kept.end(), [&](auto i) { return i < limit; }));
}

TEST(OutlierRemoval, StatisticalRemovesAllFarOutliersAndKeepsTheSurface) {
    const PointCloud cloud = noisy_plane_with_outliers(400, 11);
    const OutlierRemovalResult result = statistical_outlier_removal(cloud, {});
    ASSERT_EQ(result.status, OutlierStatus::kOk);
    const std::size_t kept_surface = count_below(result.kept_indices, kSurfacePoints);
    EXPECT_EQ(kept_surface, result.kept_indices.size()) << "an outlier survived";
    EXPECT_GE(double(kept_surface), 0.99 * double(kSurfacePoints));
    EXPECT_EQ(result.num_removed, cloud.size() - result.kept_indices.size());
    EXPECT_TRUE(std::is_sorted(result.kept_indices.begin(), result.kept_indices.end()));
    EXPECT_GT(result.threshold_m, result.mean_distance_m);
}

TEST(OutlierRemoval, RadiusRemovesAllFarOutliersAndKeepsTheSurface) {
    const PointCloud cloud = noisy_plane_with_outliers(400, 12);
    const OutlierRemovalResult result =
        radius_outlier_removal(cloud, {.radius_m = 0.005f, .min_neighbors = 4});
    ASSERT_EQ(result.status, OutlierStatus::kOk);
    const std::size_t kept_surface = count_below(result.kept_indices, kSurfacePoints);
    EXPECT_EQ(kept_surface, result.kept_indices.size()) << "an outlier survived";
    EXPECT_GE(double(kept_surface), 0.99 * double(kSurfacePoints));
}

TEST(OutlierRemoval, NonFinitePointsAreRemovedAndCounted) {
    PointCloud cloud = noisy_plane_with_outliers(0, 13);
    cloud.positions[5] = Eigen::Vector3f(NAN, 0.0f, 0.0f);
    const OutlierRemovalResult stat = statistical_outlier_removal(cloud, {});
    EXPECT_EQ(stat.num_non_finite, 1u);
    EXPECT_FALSE(std::binary_search(stat.kept_indices.begin(), stat.kept_indices.end(), 5u));
    const OutlierRemovalResult radius = radius_outlier_removal(cloud, {});
    EXPECT_EQ(radius.num_non_finite, 1u);
}

TEST(OutlierRemoval, DegenerateInputsReportStatus) {
    EXPECT_EQ(statistical_outlier_removal(PointCloud{}, {}).status, OutlierStatus::kEmptyCloud);
    EXPECT_EQ(radius_outlier_removal(PointCloud{}, {}).status, OutlierStatus::kEmptyCloud);
    PointCloud few;
    for (int i = 0; i < 5; ++i) few.positions.emplace_back(float(i), 0.0f, 0.0f);
    const OutlierRemovalResult result = statistical_outlier_removal(few, {.k_neighbors = 16});
    EXPECT_EQ(result.status, OutlierStatus::kTooFewPoints);
    EXPECT_EQ(result.kept_indices.size(), 5u);
}

}  // namespace
}  // namespace anascan
