// Coverage on analytic data: a box whose faces are sampled on a grid (some parts left out),
// seen from known sensors; the covered fraction and the holes are known in advance.

#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <vector>

#include "anascan/processing/coverage/coverage.hpp"
#include "anascan/processing/io/coverage_ply.hpp"
#include "anascan/processing/io/ply.hpp"

namespace anascan {
namespace {

// A rectangle in 3-D: centre, two half-axes (their cross product is the outward normal).
struct Face {
    Eigen::Vector3d centre, u, v;
    Eigen::Vector3d normal() const { return u.cross(v).normalized(); }
    double area() const { return 4.0 * u.norm() * v.norm(); }
};

// The six faces of an axis-aligned box of `size` with its centre at `centre`.
std::vector<Face> box_faces(const Eigen::Vector3d& centre, const Eigen::Vector3d& size) {
    const Eigen::Vector3d h = size / 2;
    const Eigen::Vector3d x(h.x(), 0, 0), y(0, h.y(), 0), z(0, 0, h.z());
    return {{centre + x, y, z}, {centre - x, z, y}, {centre + y, z, x},
            {centre - y, x, z}, {centre + z, x, y}, {centre - z, y, x}};
}

Mesh box_mesh(const std::vector<Face>& faces) {
    Mesh mesh;
    for (const Face& f : faces) {
        const int base = static_cast<int>(mesh.vertices.size());
        for (const auto& [a, b] : {std::pair{-1, -1}, {1, -1}, {1, 1}, {-1, 1}})
            mesh.vertices.positions.push_back((f.centre + a * f.u + b * f.v).cast<float>());
        mesh.triangles.emplace_back(base, base + 1, base + 2);
        mesh.triangles.emplace_back(base, base + 2, base + 3);
    }
    return mesh;
}

// Grid points on a face every `spacing_m`, leaving out a centred square hole of half side
// `hole_half_m` (0: none).
void add_grid(PointCloud& cloud, const Face& f, double spacing_m, double hole_half_m = 0.0) {
    const double lu = f.u.norm(), lv = f.v.norm();
    const Eigen::Vector3d eu = f.u / lu, ev = f.v / lv;
    for (double a = -lu + spacing_m / 2; a < lu; a += spacing_m)
        for (double b = -lv + spacing_m / 2; b < lv; b += spacing_m) {
            if (std::abs(a) < hole_half_m && std::abs(b) < hole_half_m) continue;
            cloud.positions.push_back((f.centre + a * eu + b * ev).cast<float>());
        }
}

CoverageScanView view_of(const PointCloud& cloud, const Eigen::Vector3d& sensor) {
    return CoverageScanView{.cloud = &cloud, .sensor_origin_scan_m = sensor};
}

const Eigen::Vector3d kSize(0.3, 0.2, 0.15);
const Eigen::Vector3d kCentre(0.0, 0.0, 0.075);

TEST(Coverage, WholeBoxSeenExceptAHoleInTheTop) {
    const auto faces = box_faces(kCentre, kSize);
    std::vector<PointCloud> clouds(faces.size());
    std::vector<CoverageScanView> views;
    for (std::size_t i = 0; i < faces.size(); ++i) {
        add_grid(clouds[i], faces[i], 0.001, i == 4 ? 0.03 : 0.0);
        views.push_back(view_of(clouds[i], faces[i].centre + 0.5 * faces[i].normal()));
    }
    const CoverageReport report = compute_coverage_on_surface(box_mesh(faces), views, {});
    ASSERT_EQ(report.status, CoverageStatus::kOk) << report.message;
    double total = 0.0;
    for (const Face& f : faces) total += f.area();
    EXPECT_NEAR(report.surface_area_m2, total, 1e-6);
    // The 6 x 6 cm hole shrinks by about the cylinder radius on each side.
    const double hole = 0.06 * 0.06;
    EXPECT_NEAR(report.fraction, 1.0 - hole / total, 0.01);
    ASSERT_EQ(report.holes.size(), 1u);
    EXPECT_GT(report.holes[0].area_m2, 0.5 * hole);
    EXPECT_LT(report.holes[0].area_m2, 1.1 * hole);
    EXPECT_LT((report.holes[0].centre_m - faces[4].centre).norm(), 0.005);
    EXPECT_GT(report.holes[0].normal.dot(Eigen::Vector3d::UnitZ()), 0.999);
    EXPECT_EQ(report.samples.size(), report.sample_states.size());
    EXPECT_EQ(report.samples.colors.size(), report.samples.size());
}

TEST(Coverage, TooSparseOrTooGrazingIsNotObserved) {
    const auto faces = box_faces(kCentre, kSize);
    const Face& top = faces[4];
    PointCloud dense, sparse;
    add_grid(dense, top, 0.001);
    add_grid(sparse, top, 0.005);  // 4 points per cm², below the default 10
    Mesh top_mesh = box_mesh({top});
    const Eigen::Vector3d above = top.centre + Eigen::Vector3d(0, 0, 0.8);
    // 80° from the normal: grazing.
    const Eigen::Vector3d grazing =
        top.centre + 0.8 * Eigen::Vector3d(std::sin(80 * M_PI / 180), 0, std::cos(80 * M_PI / 180));
    const Eigen::Vector3d behind = top.centre - Eigen::Vector3d(0, 0, 0.8);
    const CoverageScanView dense_above[] = {view_of(dense, above)};
    const CoverageScanView sparse_above[] = {view_of(sparse, above)};
    const CoverageScanView dense_grazing[] = {view_of(dense, grazing)};
    const CoverageScanView dense_behind[] = {view_of(dense, behind)};
    EXPECT_GT(compute_coverage_on_surface(top_mesh, dense_above, {}).fraction, 0.97);
    const CoverageReport thin = compute_coverage_on_surface(top_mesh, sparse_above, {});
    EXPECT_LT(thin.fraction, 0.05);
    EXPECT_GT(thin.sparse_area_m2, 0.9 * top.area());
    const CoverageReport flat = compute_coverage_on_surface(top_mesh, dense_grazing, {});
    EXPECT_LT(flat.fraction, 0.05);
    EXPECT_GT(flat.sparse_area_m2, 0.9 * top.area());
    // Seen from behind: the points belong to another surface.
    const CoverageReport back = compute_coverage_on_surface(top_mesh, dense_behind, {});
    EXPECT_LT(back.fraction + back.sparse_area_m2, 0.05);
    // A lower threshold (one point in the 0.5 cm² disc) accepts the sparse scan.
    EXPECT_GT(
        compute_coverage_on_surface(top_mesh, sparse_above, {.min_density_per_cm2 = 1.5}).fraction,
        0.97);
}

// Views of the box standing on a ground plane from four sides, upper faces only (the
// bottom rests on the ground): the estimate (hull of the stone points) agrees with the
// truth, and the bottom is the largest hole.
struct GroundScene {
    std::vector<PointCloud> clouds;
    std::vector<CoverageScanView> views;
};

GroundScene box_on_ground(const std::vector<Face>& faces) {
    GroundScene scene;
    scene.clouds.resize(4);
    for (int k = 0; k < 4; ++k) {
        const double az = (45.0 + 90.0 * k) * M_PI / 180;
        const Eigen::Vector3d sensor =
            kCentre + 0.9 * Eigen::Vector3d(std::cos(az) * 0.77, std::sin(az) * 0.77, 0.64);
        PointCloud& cloud = scene.clouds[k];
        for (const Face& f : faces)
            if (f.normal().dot(sensor - f.centre) > 0.0 && f.normal().z() > -0.5)
                add_grid(cloud, f, 0.0015);
        for (double x = -0.6; x < 0.6; x += 0.005)
            for (double y = -0.6; y < 0.6; y += 0.005)
                if (std::abs(x) > kSize.x() / 2 || std::abs(y) > kSize.y() / 2)
                    cloud.positions.emplace_back(x, y, 0.0f);
        // A tripod leg far away: background, not stone.
        for (double z = 0.01; z < 0.5; z += 0.002) cloud.positions.emplace_back(0.5f, 0.5f, z);
        // Each scan in its own frame: a known pose.
        const Pose T_world_scan = Pose(Eigen::Translation3d(sensor) *
                                       Eigen::AngleAxisd(0.3 * (k + 1), Eigen::Vector3d::UnitZ()));
        for (auto& p : cloud.positions)
            p = (T_world_scan.inverse() * p.cast<double>()).cast<float>();
        scene.views.push_back(CoverageScanView{.cloud = &cloud,
                                               .T_world_scan = T_world_scan,
                                               .sensor_origin_scan_m = Eigen::Vector3d::Zero()});
    }
    return scene;
}

TEST(Coverage, EstimateOnGroundAgreesWithTruthAndMissesTheBottom) {
    const auto faces = box_faces(kCentre, kSize);
    const GroundScene scene = box_on_ground(faces);
    const CoverageReport estimate = compute_coverage(scene.views, {});
    const CoverageReport truth = compute_coverage_on_surface(box_mesh(faces), scene.views, {});
    ASSERT_EQ(estimate.status, CoverageStatus::kOk) << estimate.message;
    const double bottom = faces[5].area();
    double total = 0.0;
    for (const Face& f : faces) total += f.area();
    EXPECT_NEAR(truth.fraction, 1.0 - bottom / total, 0.01);
    EXPECT_NEAR(estimate.fraction, truth.fraction, 0.02);
    EXPECT_NEAR(estimate.surface_area_m2, total, 0.03 * total);
    ASSERT_FALSE(estimate.holes.empty());
    EXPECT_NEAR(estimate.holes[0].area_m2, bottom, 0.1 * bottom);
    EXPECT_LT(estimate.holes[0].normal.dot(Eigen::Vector3d::UnitZ()), -0.99);
    EXPECT_LT((estimate.holes[0].centre_m.head<2>() - kCentre.head<2>()).norm(), 0.01);
}

TEST(Coverage, NoScansAndNoStoneAreReported) {
    EXPECT_EQ(compute_coverage({}, {}).status, CoverageStatus::kNoScans);
    PointCloud ground;
    for (double x = -0.5; x < 0.5; x += 0.01)
        for (double y = -0.5; y < 0.5; y += 0.01) ground.positions.emplace_back(x, y, 0.0f);
    const CoverageScanView views[] = {view_of(ground, Eigen::Vector3d(0, 0, 1))};
    // A flat floor alone: nothing stands on it, so nothing spans a volume.
    const CoverageReport report = compute_coverage(views, {});
    EXPECT_NE(report.status, CoverageStatus::kOk);
    EXPECT_FALSE(report.message.empty());
    EXPECT_NE(coverage_to_json(report).find(std::string("\"") + to_string(report.status) + "\""),
              std::string::npos);
}

TEST(Coverage, PlyAndJsonOfTheSamples) {
    const auto faces = box_faces(kCentre, kSize);
    PointCloud top;
    add_grid(top, faces[4], 0.001);
    const CoverageScanView views[] = {view_of(top, faces[4].centre + Eigen::Vector3d(0, 0, 0.5))};
    const CoverageReport report = compute_coverage_on_surface(box_mesh(faces), views, {});
    const auto dir = std::filesystem::temp_directory_path() / "anascan_test_coverage";
    std::filesystem::create_directories(dir);
    ASSERT_TRUE(io::write_coverage_ply(dir / "coverage.ply", report).has_value());
    const auto read = io::read_ply(dir / "coverage.ply");
    ASSERT_TRUE(read.has_value()) << read.error().message;
    EXPECT_EQ(read->cloud.size(), report.samples.size());
    EXPECT_EQ(read->cloud.colors, report.samples.colors);
    const auto empty = io::write_coverage_ply(dir / "empty.ply", CoverageReport{});
    ASSERT_FALSE(empty.has_value());
    EXPECT_NE(empty.error().message.find("empty.ply"), std::string::npos);
    std::filesystem::remove_all(dir);
    const std::string json = coverage_to_json(report, 1);
    EXPECT_NE(json.find("\"fraction\": "), std::string::npos);
    EXPECT_NE(json.find("\"holes\": [{\"area_m2\""), std::string::npos);
}

}  // namespace
}  // namespace anascan
