// The fit of Poisson's vertices to the measured points (fit_to_points.cpp) and the midpoint
// subdivision that precedes it when the octree is coarser than asked (subdivide.cpp), on a
// box with sharp arrises: the surface Poisson's octree rounds most.
#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <random>

#include "anascan/processing/surface/mesh_distance.hpp"
#include "anascan/processing/surface/mesh_topology.hpp"
#include "anascan/processing/surface/model_report.hpp"
#include "anascan/processing/surface/reconstruction.hpp"
#include "surface/subdivide.hpp"

namespace anascan {
namespace {

constexpr double kHalf = 0.03;  // a 60 mm cube centred on the origin

Eigen::Vector3d on_box(std::mt19937& rng, Eigen::Vector3d& normal) {
    std::uniform_int_distribution<int> face(0, 5);
    std::uniform_real_distribution<double> u(-kHalf, kHalf);
    const int f = face(rng);
    const int axis = f / 2;
    const double sign = f % 2 ? -1.0 : 1.0;
    Eigen::Vector3d p(u(rng), u(rng), u(rng));
    p[axis] = sign * kHalf;
    normal = Eigen::Vector3d::Zero();
    normal[axis] = sign;
    return p;
}

struct BoxScans {
    std::vector<PointCloud> clouds;
    std::vector<Eigen::Vector3d> sensors;
    std::vector<PlacedScan> placed() const {
        std::vector<PlacedScan> out;
        for (std::size_t i = 0; i < clouds.size(); ++i) out.push_back({&clouds[i], sensors[i]});
        return out;
    }
};

// Eight sensors toward the corners: each sees three faces, every face is seen by four.
BoxScans scan_box(double spacing_m, double noise_m, unsigned seed) {
    BoxScans s;
    std::mt19937 rng(seed);
    std::normal_distribution<double> gauss(0.0, 1.0);
    const auto n = static_cast<std::size_t>(24.0 * kHalf * kHalf / (spacing_m * spacing_m));
    for (int c = 0; c < 8; ++c) {
        const Eigen::Vector3d sensor =
            0.3 * Eigen::Vector3d(c & 1 ? 1 : -1, c & 2 ? 1 : -1, c & 4 ? 1 : -1).normalized();
        PointCloud cloud;
        for (std::size_t i = 0; i < n; ++i) {
            Eigen::Vector3d normal;
            const Eigen::Vector3d p = on_box(rng, normal);
            if (normal.dot((sensor - p).normalized()) < 0.25) continue;
            cloud.positions.push_back((p + noise_m * gauss(rng) * normal).cast<float>());
        }
        s.clouds.push_back(std::move(cloud));
        s.sensors.push_back(sensor);
    }
    return s;
}

// Share of uniform samples of the true box within `tolerance_m` of the model.
double completeness(const FragmentModel& model, double tolerance_m) {
    const MeshDistance distance(model.mesh);
    std::mt19937 rng(99);
    int within = 0;
    const int samples = 20000;
    for (int i = 0; i < samples; ++i) {
        Eigen::Vector3d normal;
        within += distance.distance_m(on_box(rng, normal)) <= tolerance_m;
    }
    return double(within) / samples;
}

// A sphere with relief: r = R + A sin(k u_x) sin(k u_y) sin(k u_z) in the unit direction u
// (a wavelength of about 10 mm at R = 50 mm); its scans from six directions.
constexpr double kR = 0.05, kA = 1e-3, kK = 30.0;

double relief_radius(const Eigen::Vector3d& u) {
    return kR + kA * std::sin(kK * u.x()) * std::sin(kK * u.y()) * std::sin(kK * u.z());
}

BoxScans scan_relief(double spacing_m, double noise_m, unsigned seed) {
    BoxScans s;
    std::mt19937 rng(seed);
    std::normal_distribution<double> gauss(0.0, 1.0);
    const auto n = static_cast<std::size_t>(4.0 * M_PI * kR * kR / (spacing_m * spacing_m));
    const Eigen::Vector3d dirs[] = {{1, 0, 0},  {-1, 0, 0}, {0, 1, 0},
                                    {0, -1, 0}, {0, 0, 1},  {0, 0, -1}};
    for (const Eigen::Vector3d& dir : dirs) {
        const Eigen::Vector3d sensor = 0.4 * dir;
        PointCloud cloud;
        for (std::size_t i = 0; i < n; ++i) {
            const Eigen::Vector3d u =
                Eigen::Vector3d(gauss(rng), gauss(rng), gauss(rng)).normalized();
            const Eigen::Vector3d p = relief_radius(u) * u;
            if (u.dot((sensor - p).normalized()) < 0.25) continue;
            cloud.positions.push_back((p + noise_m * gauss(rng) * u).cast<float>());
        }
        s.clouds.push_back(std::move(cloud));
        s.sensors.push_back(sensor);
    }
    return s;
}

// 95th percentile of the radial distance from the model's surface to the relief.
double relief_error_p95(const FragmentModel& model) {
    std::vector<double> d;
    for (const SurfaceSample& s : sample_surface(model.mesh, 0.5e-3)) {
        const double r = s.position_m.norm();
        d.push_back(std::abs(r - relief_radius(s.position_m / r)));
    }
    auto at = d.begin() + std::ptrdiff_t(d.size() * 95 / 100);
    std::nth_element(d.begin(), at, d.end());
    return *at;
}

TEST(FitToPoints, RecoversReliefTheOctreeSmoothsAway) {
    const BoxScans scans = scan_relief(0.5e-3, 5e-5, 1);
    // The default path at 1 mm (an octree up to twice as coarse), with Poisson's vertices
    // and with the vertices fitted to the points.
    const SurfaceConfig fitted{.resolution_m = 1e-3};
    SurfaceConfig raw = fitted;
    raw.fit_to_points = false;
    const SurfaceResult a = reconstruct_surface(scans.placed(), raw);
    const SurfaceResult b = reconstruct_surface(scans.placed(), fitted);
    ASSERT_EQ(a.status, SurfaceStatus::kOk);
    ASSERT_EQ(b.status, SurfaceStatus::kOk);
    ASSERT_EQ(a.diagnostics.poisson_depth, b.diagnostics.poisson_depth);
    EXPECT_EQ(a.diagnostics.vertices_fitted, 0u);
    EXPECT_GT(b.diagnostics.vertices_fitted, b.model.mesh.vertices.size() * 9 / 10);
    const double before = relief_error_p95(a.model), after = relief_error_p95(b.model);
    EXPECT_LT(after, 0.8 * before) << "p95 before " << before << " m, after " << after << " m";
    const ModelReport report = make_model_report(b.model, b.merged);
    EXPECT_TRUE(report.closed);
    EXPECT_TRUE(report.manifold);
}

TEST(FitToPoints, TheDefaultModelIsCompleteWithinHalfTheResolution) {
    const BoxScans scans = scan_box(0.5e-3, 2e-5, 3);
    const SurfaceResult r = reconstruct_surface(scans.placed(), {.resolution_m = 1e-3});
    ASSERT_EQ(r.status, SurfaceStatus::kOk);
    EXPECT_GT(completeness(r.model, 0.5e-3), 0.99);
}

TEST(FitToPoints, ACoarseOctreeIsSubdividedBackToTheResolution) {
    const BoxScans scans = scan_box(0.5e-3, 2e-5, 2);
    const SurfaceResult fine = reconstruct_surface(scans.placed(), {.resolution_m = 1e-3});
    const SurfaceResult coarse = reconstruct_surface(
        scans.placed(),
        {.resolution_m = 1e-3, .max_memory_bytes = fine.diagnostics.estimated_memory_bytes / 3});
    ASSERT_EQ(coarse.status, SurfaceStatus::kOk);
    ASSERT_LT(coarse.diagnostics.poisson_depth, fine.diagnostics.poisson_depth);
    EXPECT_EQ(fine.diagnostics.subdivisions, 0);
    EXPECT_EQ(coarse.diagnostics.subdivisions, 1);
    const ModelReport report = make_model_report(coarse.model, coarse.merged);
    EXPECT_TRUE(report.closed);
    EXPECT_TRUE(report.manifold);
    EXPECT_GT(completeness(coarse.model, 0.5e-3), 0.98);
}

TEST(Subdivide, KeepsAClosedMeshClosedAndItsShape) {
    Mesh tetra;
    tetra.vertices.positions = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {0, 0, 1}};
    tetra.triangles = {{0, 2, 1}, {0, 1, 3}, {0, 3, 2}, {1, 2, 3}};
    const Mesh once = surface_detail::subdivide_midpoints(tetra);
    EXPECT_EQ(once.triangles.size(), 16u);
    EXPECT_EQ(once.vertices.size(), 4u + 6u);  // one new vertex per edge
    const MeshTopology topo = analyse_topology(once);
    EXPECT_TRUE(topo.closed());
    EXPECT_TRUE(topo.manifold());
    EXPECT_EQ(topo.inconsistent_edges, 0u);
    EXPECT_EQ(topo.components, 1u);
    const MeshDistance original(tetra);
    for (std::size_t v = 0; v < once.vertices.size(); ++v)
        EXPECT_LT(original.distance_m(once.vertices.world_position(v)), 1e-6);
}

}  // namespace
}  // namespace anascan
