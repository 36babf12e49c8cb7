// Dominant plane (the ground under a stone) against analytic scenes.

#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <cmath>
#include <numbers>
#include <random>

#include "anascan/processing/cleaning/plane_removal.hpp"

namespace anascan {
namespace {

constexpr double kDegree = std::numbers::pi / 180.0;

struct Scene {
    PointCloud cloud;
    std::size_t ground_points = 0;  // The first points of the cloud.
};

// A 1 m square of ground (a tilted plane through `on_ground` with normal `up`) holding a
// 0.3 x 0.2 x 0.25 m box; random samples, Gaussian noise of `noise_m` along all axes.
Scene box_on_ground(const Eigen::Vector3d& up, const Eigen::Vector3d& on_ground, double noise_m,
                    std::uint64_t seed) {
    std::mt19937_64 rng(seed);
    std::uniform_real_distribution<double> unit(0.0, 1.0);
    std::normal_distribution<double> noise(0.0, noise_m);
    const Eigen::Quaterniond tilt =
        Eigen::Quaterniond::FromTwoVectors(Eigen::Vector3d::UnitZ(), up);
    Scene scene;
    auto add = [&](const Eigen::Vector3d& p) {
        const Eigen::Vector3d n(noise(rng), noise(rng), noise(rng));
        scene.cloud.positions.push_back((on_ground + tilt * p + n).cast<float>());
    };
    for (int i = 0; i < 40000; ++i) add({unit(rng) - 0.5, unit(rng) - 0.5, 0.0});
    scene.ground_points = scene.cloud.size();
    const Eigen::Vector3d size(0.3, 0.2, 0.25);
    for (int i = 0; i < 15000; ++i) {  // Box faces except the bottom.
        Eigen::Vector3d p(unit(rng), unit(rng), unit(rng));
        const int face = i % 5;
        if (face < 4)
            p[face / 2] = double(face % 2);
        else
            p.z() = 1.0;
        add(p.cwiseProduct(size) - Eigen::Vector3d(0.15, 0.1, 0.0));
    }
    return scene;
}

void expect_ground(const PlaneFitResult& fit, const Eigen::Vector3d& up,
                   const Eigen::Vector3d& on_ground) {
    ASSERT_EQ(fit.status, PlaneFitStatus::kOk);
    EXPECT_LT(std::acos(std::min(fit.plane.normal.dot(up), 1.0)), 0.1 * kDegree);
    EXPECT_NEAR(fit.plane.normal.norm(), 1.0, 1e-9);
    EXPECT_LT(std::abs(fit.plane.normal.dot(on_ground) + fit.plane.offset_m), 0.0005);
}

TEST(PlaneRemoval, FindsTheGroundUnderABox) {
    const Eigen::Vector3d up = Eigen::Vector3d(0.1, -0.05, 1.0).normalized();
    const Eigen::Vector3d on_ground(0.3, 0.2, -1.5);
    const Scene scene = box_on_ground(up, on_ground, 0.0, 1);
    const PlaneFitResult fit = find_dominant_plane(scene.cloud, {});
    expect_ground(fit, up, on_ground);
    EXPECT_NEAR(fit.inlier_fraction, 40000.0 / 55000.0, 0.02);
    // The box walls' lowest 2 mm lie in the inlier band: rms ~ 2 mm * sqrt(fraction / 3).
    EXPECT_LT(fit.rms_m, 2e-4);
}

TEST(PlaneRemoval, FindsTheGroundWithNoiseAndRemovesIt) {
    const Eigen::Vector3d up = Eigen::Vector3d(-0.2, 0.1, 1.0).normalized();
    const Eigen::Vector3d on_ground(-0.4, 1.0, 0.7);
    const Scene scene = box_on_ground(up, on_ground, 0.0005, 2);
    const PlaneRemovalResult removal =
        remove_dominant_plane(scene.cloud, {.distance_threshold_m = 0.002});
    expect_ground(removal.fit, up, on_ground);
    std::size_t ground_kept = 0;
    for (const std::size_t i : removal.kept_indices) ground_kept += i < scene.ground_points;
    EXPECT_LT(ground_kept, scene.ground_points / 100);
    EXPECT_GT(removal.kept_indices.size() - ground_kept, 14000u);  // The box stays.
}

TEST(PlaneRemoval, SameSeedSameResult) {
    const Scene scene = box_on_ground(Eigen::Vector3d::UnitZ(), Eigen::Vector3d::Zero(), 0.001, 3);
    const PlaneFitResult a = find_dominant_plane(scene.cloud, {.seed = 42});
    const PlaneFitResult b = find_dominant_plane(scene.cloud, {.seed = 42});
    EXPECT_EQ(a.plane.normal, b.plane.normal);
    EXPECT_EQ(a.inlier_indices, b.inlier_indices);
    EXPECT_EQ(a.iterations, b.iterations);
}

TEST(PlaneRemoval, NoDominantPlaneOnASphere) {
    PointCloud cloud;
    std::mt19937_64 rng(4);
    std::normal_distribution<float> gauss(0.0f, 1.0f);
    for (int i = 0; i < 20000; ++i) {
        cloud.positions.push_back(0.1f *
                                  Eigen::Vector3f(gauss(rng), gauss(rng), gauss(rng)).normalized());
    }
    const PlaneRemovalResult removal = remove_dominant_plane(cloud, {});
    EXPECT_EQ(removal.fit.status, PlaneFitStatus::kNoDominantPlane);
    EXPECT_LT(removal.fit.inlier_fraction, 0.2);
    EXPECT_EQ(removal.kept_indices.size(), cloud.size());
}

TEST(PlaneRemoval, TooFewOrDegeneratePoints) {
    PointCloud two;
    two.positions = {Eigen::Vector3f::Zero(), Eigen::Vector3f::UnitX()};
    EXPECT_EQ(find_dominant_plane(two, {}).status, PlaneFitStatus::kTooFewPoints);
    PointCloud line;
    for (int i = 0; i < 100; ++i) line.positions.emplace_back(float(i), 0.0f, 0.0f);
    const PlaneFitResult fit = find_dominant_plane(line, {});
    EXPECT_TRUE(fit.plane.normal.allFinite());
    EXPECT_TRUE(std::isfinite(fit.plane.offset_m));
}

}  // namespace
}  // namespace anascan
