// The volume descriptor V_r (paper eq. 1) against closed forms on analytic shapes: a plane
// (1/2), spheres seen from outside (convex) and inside (a cavity, concave) against the exact
// ball–ball intersection fraction, a cylinder against 1/2 − 3r/(32R), and the scan boundary.
#include <gtest/gtest.h>

#include <Eigen/Core>
#include <cmath>
#include <numbers>

#include "anascan/processing/features/integral_invariants.hpp"

namespace anascan {
namespace {

constexpr double kPi = std::numbers::pi;

// Volume of the intersection of balls of radii a and b whose centres are d apart
// (0 <= d <= a + b, lens formula), metres cubed.
double ball_intersection_volume(double a, double b, double d) {
    const double s = a + b - d;
    return kPi * s * s *
           (d * d + 2.0 * d * b - 3.0 * b * b + 2.0 * d * a + 6.0 * b * a - 3.0 * a * a) /
           (12.0 * d);
}

// Exact V_r at a point of a sphere of radius R when the solid is the ball (convex side).
double sphere_volume_fraction(double r, double big_r) {
    return ball_intersection_volume(big_r, r, big_r) / (4.0 / 3.0 * kPi * r * r * r);
}

// Square grid in z = 0, normals +z (solid below).
PointCloud plane_grid(double half_size_m, double spacing_m) {
    PointCloud cloud;
    const int n = static_cast<int>(std::round(half_size_m / spacing_m));
    for (int i = -n; i <= n; ++i) {
        for (int j = -n; j <= n; ++j) {
            cloud.positions.emplace_back(float(i * spacing_m), float(j * spacing_m), 0.0f);
            cloud.normals.emplace_back(0.0f, 0.0f, 1.0f);
        }
    }
    return cloud;
}

// Fibonacci sphere (uniform per area) of radius R about the origin; normals outward, or
// inward for a cavity (solid outside the sphere).
PointCloud fibonacci_sphere(double big_r, double spacing_m, bool cavity) {
    PointCloud cloud;
    const auto n = static_cast<std::size_t>(4.0 * kPi * big_r * big_r / (spacing_m * spacing_m));
    const double golden = kPi * (3.0 - std::sqrt(5.0));
    for (std::size_t i = 0; i < n; ++i) {
        const double z = 1.0 - 2.0 * (static_cast<double>(i) + 0.5) / static_cast<double>(n);
        const double rho = std::sqrt(1.0 - z * z);
        const Eigen::Vector3d u(rho * std::cos(golden * i), rho * std::sin(golden * i), z);
        cloud.positions.push_back((big_r * u).cast<float>());
        cloud.normals.push_back((cavity ? -u : u).cast<float>());
    }
    return cloud;
}

// Cylinder of radius R about the z axis, |z| <= half length, normals outward.
PointCloud cylinder(double big_r, double half_length_m, double spacing_m) {
    PointCloud cloud;
    const int around = static_cast<int>(2.0 * kPi * big_r / spacing_m);
    const int along = static_cast<int>(half_length_m / spacing_m);
    for (int a = 0; a < around; ++a) {
        const double phi = 2.0 * kPi * a / around;
        const Eigen::Vector3f u(float(std::cos(phi)), float(std::sin(phi)), 0.0f);
        for (int j = -along; j <= along; ++j) {
            cloud.positions.push_back(float(big_r) * u +
                                      Eigen::Vector3f(0.0f, 0.0f, float(j * spacing_m)));
            cloud.normals.push_back(u);
        }
    }
    return cloud;
}

IntegralInvariantConfig test_config() {
    return {.radii_m = geometric_radii_m(0.006), .site_spacing_m = 0.004};
}

TEST(IntegralInvariantClosedForm, BallOnSphereFractionIsTheCurvatureApproximation) {
    for (double big_r : {0.02, 0.05, 0.1}) {
        for (double r : {0.002, 0.01, 0.02}) {
            EXPECT_NEAR(sphere_volume_fraction(r, big_r), 0.5 - 3.0 * r / (16.0 * big_r), 1e-12);
        }
    }
}

TEST(IntegralInvariant, PlaneGivesOneHalfInsideAndInvalidAtTheBoundary) {
    const PointCloud cloud = plane_grid(0.1, 0.001);
    const IntegralInvariantResult result = compute_integral_invariants(cloud, test_config());
    ASSERT_EQ(result.status, IntegralInvariantStatus::kOk);
    for (std::size_t k = 0; k < kInvariantRadii; ++k) {
        const double r = result.radii_m[k];
        std::size_t interior = 0;
        for (std::size_t i = 0; i < result.site_positions.size(); ++i) {
            const double edge = 0.1 - result.site_positions[i].head<2>().cwiseAbs().maxCoeff();
            if (edge > r) {
                ASSERT_TRUE(result.is_valid(i, k)) << "interior site, r = " << r;
                EXPECT_NEAR(result.volume[i][k], 0.5, 1e-4);
                ++interior;
            } else if (edge < 0.05 * r) {
                EXPECT_FALSE(result.is_valid(i, k)) << "boundary site, r = " << r;
            }
        }
        EXPECT_GT(interior, 100u);
        EXPECT_GT(result.boundary_count[k], 0u);
    }
}

void expect_sphere(double big_r, bool cavity) {
    const PointCloud cloud = fibonacci_sphere(big_r, 0.0008, cavity);
    const IntegralInvariantResult result = compute_integral_invariants(cloud, test_config());
    ASSERT_EQ(result.status, IntegralInvariantStatus::kOk);
    for (std::size_t k = 0; k < kInvariantRadii; ++k) {
        const double r = result.radii_m[k];
        const double convex = sphere_volume_fraction(r, big_r);
        const double expected = cavity ? 1.0 - convex : convex;
        double sum = 0.0;
        for (std::size_t i = 0; i < result.site_positions.size(); ++i) {
            ASSERT_TRUE(result.is_valid(i, k)) << "closed sphere has no boundary";
            // Per site, the down-sampled samples are not exactly uniform per area.
            EXPECT_NEAR(result.volume[i][k], expected, 0.003 + 0.08 * std::abs(expected - 0.5))
                << "R = " << big_r << " r = " << r;
            sum += result.volume[i][k];
        }
        EXPECT_NEAR(sum / result.site_positions.size(), expected, 0.002);
    }
}

TEST(IntegralInvariant, ConvexSpheresMatchBallIntersectionVolume) {
    for (double big_r : {0.03, 0.05, 0.1}) expect_sphere(big_r, false);
}

TEST(IntegralInvariant, ConcaveSphericalCavitiesMatchComplementaryVolume) {
    for (double big_r : {0.03, 0.05}) expect_sphere(big_r, true);
}

TEST(IntegralInvariant, CylinderFollowsHalfMeanCurvature) {
    const double big_r = 0.04;
    const PointCloud cloud = cylinder(big_r, 0.08, 0.001);
    const IntegralInvariantResult result = compute_integral_invariants(cloud, test_config());
    ASSERT_EQ(result.status, IntegralInvariantStatus::kOk);
    for (std::size_t k = 0; k < kInvariantRadii; ++k) {
        const double r = result.radii_m[k];
        const double expected = 0.5 - 3.0 * r / (32.0 * big_r);  // H = 1 / (2R).
        std::size_t checked = 0;
        double sum = 0.0;
        for (std::size_t i = 0; i < result.site_positions.size(); ++i) {
            if (std::abs(result.site_positions[i].z()) > 0.08 - 1.5 * r) continue;
            ASSERT_TRUE(result.is_valid(i, k));
            EXPECT_NEAR(result.volume[i][k], expected, 0.003 + 0.1 * (0.5 - expected));
            sum += result.volume[i][k];
            ++checked;
        }
        EXPECT_GT(checked, 100u);
        EXPECT_NEAR(sum / static_cast<double>(checked), expected, 0.002 + 0.05 * (0.5 - expected));
    }
}

TEST(IntegralInvariant, RadiusHelpersAreGeometric) {
    const InvariantRadii radii = radii_for_object_size_m(0.2);
    EXPECT_NEAR(radii[0], 0.008, 1e-12);
    for (std::size_t k = 1; k < kInvariantRadii; ++k)
        EXPECT_NEAR(radii[k] / radii[k - 1], 1.5, 1e-12);
    EXPECT_NEAR(median_sample_spacing_m(plane_grid(0.02, 0.001)), 0.001, 1e-6);
}

TEST(IntegralInvariant, MissingNormalsOrBadRadiiAreInvalidInput) {
    PointCloud cloud = plane_grid(0.02, 0.001);
    IntegralInvariantConfig config = test_config();
    config.radii_m[2] = 0.0;
    EXPECT_EQ(compute_integral_invariants(cloud, config).status,
              IntegralInvariantStatus::kInvalidInput);
    cloud.normals.clear();
    EXPECT_EQ(compute_integral_invariants(cloud, test_config()).status,
              IntegralInvariantStatus::kInvalidInput);
    EXPECT_EQ(compute_integral_invariants(PointCloud{}, test_config()).status,
              IntegralInvariantStatus::kInvalidInput);
}

}  // namespace
}  // namespace anascan
