#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <cmath>
#include <limits>

#include "anascan/processing/surface/mesh_distance.hpp"
#include "anascan/processing/surface/mesh_topology.hpp"
#include "anascan/processing/surface/model_report.hpp"
#include "surface_test_scans.hpp"

namespace anascan {
namespace {

double area_share(const FragmentModel& m, SurfaceClass cls, double z_lo, double z_hi) {
    double total = 0, of_class = 0;
    const auto& p = m.mesh.vertices.positions;
    for (std::size_t t = 0; t < m.mesh.triangles.size(); ++t) {
        const Eigen::Vector3i& tri = m.mesh.triangles[t];
        const Eigen::Vector3f c = (p[tri[0]] + p[tri[1]] + p[tri[2]]) / 3.0f;
        const double z = c.z() + m.mesh.vertices.origin_m.z();
        if (z < z_lo || z > z_hi) continue;
        const double a = 0.5 * (p[tri[1]] - p[tri[0]]).cross(p[tri[2]] - p[tri[0]]).norm();
        total += a;
        if (m.triangle_class[t] == cls) of_class += a;
    }
    return total > 0 ? of_class / total : 0.0;
}

TEST(SurfaceReconstruction, SphereSeenAllRoundIsClosedAndAccurate) {
    for (const unsigned seed : {1u, 2u}) {
        const test::SphereScans scans = test::scan_sphere(test::all_round(), 1.5e-3, 1e-4, seed);
        const SurfaceResult r = reconstruct_surface(scans.placed(), {.resolution_m = 2e-3});
        ASSERT_EQ(r.status, SurfaceStatus::kOk);
        ASSERT_TRUE(r.model.consistent());
        const ModelReport report = make_model_report(r.model, r.merged);
        EXPECT_TRUE(report.closed);
        EXPECT_TRUE(report.manifold);
        EXPECT_EQ(report.components, 1u);
        const double truth_volume = 4.0 / 3.0 * M_PI * std::pow(scans.radius_m, 3);
        EXPECT_NEAR(report.volume_m3 / truth_volume, 1.0, 0.01) << "seed " << seed;
        EXPECT_NEAR(report.obb_mm.x(), 100.0, 1.0);
        EXPECT_LT(report.interpolated_area_share, 0.01);
        EXPECT_LT(report.accuracy_p95_m, 5e-4);
        // Every vertex lies on the sphere (analytic oracle).
        double worst = 0;
        for (std::size_t v = 0; v < r.model.mesh.vertices.size(); ++v) {
            worst = std::max(
                worst, std::abs(r.model.mesh.vertices.world_position(v).norm() - scans.radius_m));
        }
        EXPECT_LT(worst, 1.5e-3);
    }
}

TEST(SurfaceReconstruction, NeverSeenCapIsInterpolated) {
    const test::SphereScans scans = test::scan_sphere(test::from_above(), 1.5e-3, 1e-4, 3);
    const SurfaceResult r = reconstruct_surface(scans.placed(), {.resolution_m = 2e-3});
    ASSERT_EQ(r.status, SurfaceStatus::kOk);
    const double R = scans.radius_m;
    EXPECT_GT(area_share(r.model, SurfaceClass::kInterpolated, -R, -0.6 * R), 0.95);
    EXPECT_LT(area_share(r.model, SurfaceClass::kInterpolated, 0.0, R), 0.02);
    // The largest hole of the measured surface is the bottom. (Whether the Poisson surface
    // closes there depends on it staying inside Poisson's box: not asserted.)
    const ModelReport report = make_model_report(r.model, r.merged);
    ASSERT_FALSE(report.holes.empty());
    EXPECT_LT(report.holes.front().centroid_m.z(), -0.2 * R);
}

TEST(SurfaceReconstruction, MeasuredModeLeavesTheHoleOpen) {
    const test::SphereScans scans = test::scan_sphere(test::from_above(), 1.5e-3, 1e-4, 4);
    const SurfaceResult r =
        reconstruct_surface(scans.placed(), {.resolution_m = 2e-3, .mode = SurfaceMode::kMeasured});
    ASSERT_EQ(r.status, SurfaceStatus::kOk);
    EXPECT_GT(r.diagnostics.triangles_removed, 0u);
    for (const SurfaceClass c : r.model.triangle_class) EXPECT_EQ(c, SurfaceClass::kMeasured);
    const ModelReport report = make_model_report(r.model, r.merged);
    EXPECT_FALSE(report.closed);
    ASSERT_GE(report.holes.size(), 1u);
    // The unseen cap below z = -0.6 r (and more): at least its spherical-cap area.
    const double R = scans.radius_m;
    EXPECT_GT(report.holes.front().area_m2, 2.0 * M_PI * R * R * 0.4 * 0.5);
}

TEST(SurfaceReconstruction, WithoutSensorsOrientsConsistently) {
    const test::SphereScans scans = test::scan_sphere(test::all_round(), 1.5e-3, 1e-4, 5);
    const SurfaceResult r = reconstruct_surface(scans.placed(false), {.resolution_m = 2e-3});
    ASSERT_EQ(r.status, SurfaceStatus::kOk);
    const ModelReport report = make_model_report(r.model, r.merged);
    EXPECT_TRUE(report.closed);
    const double truth_volume = 4.0 / 3.0 * M_PI * std::pow(scans.radius_m, 3);
    EXPECT_NEAR(report.volume_m3 / truth_volume, 1.0, 0.01);  // outward: positive volume
}

TEST(SurfaceReconstruction, BadInputGivesAStatus) {
    EXPECT_EQ(reconstruct_surface({}, {}).status, SurfaceStatus::kNoPoints);
    PointCloud nan_cloud;
    nan_cloud.positions.assign(100,
                               Eigen::Vector3f::Constant(std::numeric_limits<float>::quiet_NaN()));
    const PlacedScan nan_scan{&nan_cloud, std::nullopt};
    EXPECT_EQ(reconstruct_surface({&nan_scan, 1}, {}).status, SurfaceStatus::kNoPoints);
    PointCloud few;
    for (int i = 0; i < 5; ++i) few.positions.emplace_back(0.01f * float(i), 0.0f, 0.0f);
    const PlacedScan few_scan{&few, std::nullopt};
    EXPECT_EQ(reconstruct_surface({&few_scan, 1}, {}).status, SurfaceStatus::kTooFewPoints);
    // A scan placed 10 m away shares nothing with the others.
    test::SphereScans scans = test::scan_sphere(test::all_round(), 2e-3, 1e-4, 6);
    for (Eigen::Vector3f& p : scans.clouds[2].positions) p.x() += 10.0f;
    const SurfaceResult far = reconstruct_surface(scans.placed(), {.resolution_m = 2e-3});
    EXPECT_EQ(far.status, SurfaceStatus::kIsolatedScan);
    ASSERT_EQ(far.diagnostics.isolated_scans.size(), 1u);
    EXPECT_EQ(far.diagnostics.isolated_scans[0], 2u);
}

TEST(SurfaceReconstruction, MemoryBudgetCoarsensTheOctree) {
    const test::SphereScans scans = test::scan_sphere(test::all_round(), 2e-3, 1e-4, 7);
    const SurfaceConfig config{.resolution_m = 2e-3, .octree_cell_factor = 1.0};
    const SurfaceResult fine = reconstruct_surface(scans.placed(), config);
    SurfaceConfig budget = config;
    budget.max_memory_bytes = fine.diagnostics.estimated_memory_bytes / 3;
    const SurfaceResult coarse = reconstruct_surface(scans.placed(), budget);
    ASSERT_EQ(coarse.status, SurfaceStatus::kOk);
    EXPECT_LT(coarse.diagnostics.poisson_depth, fine.diagnostics.poisson_depth);
    EXPECT_LE(coarse.diagnostics.estimated_memory_bytes,
              fine.diagnostics.estimated_memory_bytes / 3);
}

}  // namespace
}  // namespace anascan
