// compare_with_stone on sampled box views, each new scan in a random frame (the check must
// not depend on the pose): the box's other side fits; a larger box is too wide (also with two
// model scans), but not when the model's views are near duplicates; a rounded
// object of the box's size has another surface; one model scan gives no reference (how much
// a view may exceed the model, how much the surface varies), so nothing is decided.
#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <cmath>
#include <random>
#include <vector>

#include "anascan/processing/core/point_cloud.hpp"
#include "anascan/processing/core/pose.hpp"
#include "anascan/processing/evaluation/stone_identity.hpp"

namespace anascan {
namespace {

constexpr double kStepM = 0.004;
constexpr double kNoiseM = 0.0003;

void add_point(PointCloud& cloud, const Eigen::Vector3d& p, const Eigen::Vector3d& n,
               std::mt19937& rng) {
    std::normal_distribution<double> noise(0.0, kNoiseM);
    cloud.positions.push_back((p + noise(rng) * n).cast<float>());
    cloud.normals.push_back(n.cast<float>());
}

/// The faces of an axis-aligned box of `size` (centred at the origin) facing `view`,
/// sampled on a grid; a view sees the part within `reach_m` of where it aims (the box's
/// surface point along `view`), as a camera's field of view does.
PointCloud box_view(const Eigen::Vector3d& size, const Eigen::Vector3d& view, unsigned seed,
                    double reach_m = 1e9) {
    const Eigen::Vector3d aim = view.normalized().cwiseProduct(size / 2);
    std::mt19937 rng(seed);
    PointCloud cloud;
    for (int axis = 0; axis < 3; ++axis) {
        for (const double sign : {-1.0, 1.0}) {
            Eigen::Vector3d n = Eigen::Vector3d::Zero();
            n[axis] = sign;
            if (n.dot(view) <= 0.1) continue;
            const int u = (axis + 1) % 3, v = (axis + 2) % 3;
            for (double a = -size[u] / 2; a <= size[u] / 2; a += kStepM) {
                for (double b = -size[v] / 2; b <= size[v] / 2; b += kStepM) {
                    Eigen::Vector3d p = sign * size / 2;
                    p[u] = a;
                    p[v] = b;
                    if ((p - aim).norm() <= reach_m) add_point(cloud, p, n, rng);
                }
            }
        }
    }
    return cloud;
}

/// The half of a sphere of `radius_m` facing +z.
PointCloud dome(double radius_m, unsigned seed) {
    std::mt19937 rng(seed);
    PointCloud cloud;
    for (double x = -radius_m; x <= radius_m; x += kStepM) {
        for (double y = -radius_m; y <= radius_m; y += kStepM) {
            const double z2 = radius_m * radius_m - x * x - y * y;
            if (z2 < 0.0) continue;
            const Eigen::Vector3d p(x, y, std::sqrt(z2));
            add_point(cloud, p, p.normalized(), rng);
        }
    }
    return cloud;
}

PointCloud moved(const PointCloud& cloud, unsigned seed) {
    std::mt19937 rng(seed);
    std::uniform_real_distribution<double> u(-1.0, 1.0);
    const Eigen::Quaterniond q = Eigen::Quaterniond(u(rng), u(rng), u(rng), u(rng)).normalized();
    Pose T = Pose::Identity();
    T.linear() = q.toRotationMatrix();
    T.translation() = Eigen::Vector3d(u(rng), u(rng), 1.0 + u(rng));
    return transformed(cloud, T);
}

const Eigen::Vector3d kBox(0.40, 0.30, 0.25);

constexpr double kReachM = 0.25;  ///< Each view sees this far around its aim.

/// Views from above and around (the box stands on its -z face: never seen).
std::vector<PointCloud> model_of_box(std::size_t views) {
    std::vector<PointCloud> model;
    for (std::size_t k = 0; k < views; ++k) {
        const double azimuth = 0.8 + 1.6 * static_cast<double>(k);
        model.push_back(box_view(kBox, {std::cos(azimuth), std::sin(azimuth), 0.8},
                                 static_cast<unsigned>(k), kReachM));
    }
    return model;
}

TEST(StoneIdentity, TheOtherSideOfTheStoneFits) {
    const std::vector<PointCloud> model = model_of_box(4);
    const PointCloud bottom = moved(box_view(kBox, {0.5, -0.6, -0.8}, 11, kReachM), 5);
    const StoneIdentityEvidence e = compare_with_stone(model, bottom);
    EXPECT_EQ(e.verdict, StoneIdentityVerdict::kLooksSame) << e.reason;
    EXPECT_LE(e.scan_width_m, e.model_width_m + e.width_tolerance_m) << e.reason;
    EXPECT_GT(e.spacing_m, 0.5 * kStepM) << e.reason;
    EXPECT_LT(e.spacing_m, 2.0 * kStepM) << e.reason;
}

TEST(StoneIdentity, ALargerStoneIsTooWide) {
    const std::vector<PointCloud> model = model_of_box(4);
    const PointCloud larger = moved(box_view(1.6 * kBox, {0.7, 0.3, 0.8}, 12), 6);
    const StoneIdentityEvidence e = compare_with_stone(model, larger);
    EXPECT_EQ(e.verdict, StoneIdentityVerdict::kOtherStone) << e.reason;
    EXPECT_GT(e.scan_width_m, e.model_width_m + e.width_tolerance_m) << e.reason;
}

TEST(StoneIdentity, ARoundedObjectOfTheSameSizeHasAnotherSurface) {
    const std::vector<PointCloud> model = model_of_box(4);
    const PointCloud round = moved(dome(0.15, 13), 7);
    const StoneIdentityEvidence e = compare_with_stone(model, round);
    EXPECT_LE(e.scan_width_m, e.model_width_m + e.width_tolerance_m) << e.reason;
    EXPECT_EQ(e.verdict, StoneIdentityVerdict::kOtherStone) << e.reason;
    EXPECT_GT(e.surface_distance, 2.0 * e.surface_spread) << e.reason;
    EXPECT_GT(e.surface_distance, 1.0) << "most of its surface is of another kind: " << e.reason;
}

TEST(StoneIdentity, OneModelScanDecidesNothing) {
    const std::vector<PointCloud> model = model_of_box(1);
    const PointCloud larger = moved(box_view(1.6 * kBox, {0.7, 0.3, 0.8}, 12), 6);
    const StoneIdentityEvidence e = compare_with_stone(model, larger);
    EXPECT_EQ(e.verdict, StoneIdentityVerdict::kUndecided) << e.reason;
    EXPECT_LT(e.surface_distance, 0.0);
    EXPECT_LT(e.view_excess_m, 0.0);
}

TEST(StoneIdentity, TwoModelScansCompareTheSize) {
    const std::vector<PointCloud> model = model_of_box(2);
    const PointCloud larger = moved(box_view(1.6 * kBox, {0.7, 0.3, 0.8}, 12), 6);
    const StoneIdentityEvidence e = compare_with_stone(model, larger);
    EXPECT_EQ(e.verdict, StoneIdentityVerdict::kOtherStone) << e.reason;
    EXPECT_GE(e.view_excess_m, 0.0) << e.reason;
}

// Two views from one place show no more of the stone than one: a wider view of the same
// stone is not taken for another stone.
TEST(StoneIdentity, NearDuplicateViewsDoNotBoundTheSize) {
    const Eigen::Vector3d view(0.7, 0.3, 0.8);
    const std::vector<PointCloud> model = {box_view(kBox, view, 1, kReachM),
                                           box_view(kBox, view, 2, kReachM)};
    const PointCloud whole = moved(box_view(kBox, {-0.6, 0.5, 0.8}, 3), 8);
    const StoneIdentityEvidence e = compare_with_stone(model, whole);
    EXPECT_GT(e.scan_width_m, e.model_width_m + e.width_tolerance_m) << e.reason;
    EXPECT_EQ(e.verdict, StoneIdentityVerdict::kUndecided) << e.reason;
}

TEST(StoneIdentity, NothingToCompareIsUndecided) {
    const StoneIdentityEvidence e = compare_with_stone({}, box_view(kBox, {0, 0, 1}, 1));
    EXPECT_EQ(e.verdict, StoneIdentityVerdict::kUndecided);
    EXPECT_FALSE(e.reason.empty());
}

}  // namespace
}  // namespace anascan
