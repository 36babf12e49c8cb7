// Block features on analytic shapes: boxes with known size (faces, normals, width and
// height, adjacency), a bumpy face (roughness order), and the bad inputs (empty, no
// normals, a bad or non-manifold mesh, heavy noise).
#include <gtest/gtest.h>

#include <cmath>
#include <functional>
#include <numbers>
#include <random>

#include "anascan/processing/reassembly/block_features.hpp"
#include "box_mesh.hpp"

namespace anascan::reassembly {
namespace {
using testing::box_mesh;
using testing::Relief;

const PlanarFace* face_along(const BlockFeatures& f, const Eigen::Vector3d& n) {
    for (const PlanarFace& face : f.faces)
        if (face.normal.dot(n) > std::cos(5.0 * std::numbers::pi / 180.0)) return &face;
    return nullptr;
}

TEST(BlockFeatures, BoxFacesSizesAndAdjacency) {
    for (const Eigen::Vector3d& size :
         {Eigen::Vector3d(1.0, 0.6, 0.5), Eigen::Vector3d(0.45, 0.7, 0.4)}) {
        const BlockFeatures f = extract_block_features(box_mesh(size, 0.01), {});
        ASSERT_EQ(f.status, BlockStatus::kOk) << f.message;
        ASSERT_EQ(f.faces.size(), 6u);
        EXPECT_EQ(f.edges.size(), 24u);  // 12 box edges, both directions.
        for (int axis = 0; axis < 3; ++axis) {
            for (double sign : {1.0, -1.0}) {
                const Eigen::Vector3d n = sign * Eigen::Vector3d::Unit(axis);
                const PlanarFace* face = face_along(f, n);
                ASSERT_NE(face, nullptr);
                const double angle_deg =
                    std::acos(std::min(1.0, face->normal.dot(n))) * 180 / std::numbers::pi;
                EXPECT_LT(angle_deg, 0.3);
                const double a = size[(axis + 1) % 3], b = size[(axis + 2) % 3];
                EXPECT_NEAR(face->width_m, std::max(a, b), 0.005);
                EXPECT_NEAR(face->height_m, std::min(a, b), 0.005);
                EXPECT_EQ(f.neighbours(face->id).size(), 4u);
            }
        }
    }
}

// A façade eroded on 40 % of its area (up to 6 mm deep toward its +y end): the fitted plane
// is the dressed part's, not tilted toward the erosion (a fit through every inlier: 0.57°).
TEST(BlockFeatures, AFaceErodedOnOneSideKeepsItsDressedPlane) {
    const Relief erosion = [](int face, double u, double) {
        return face == 0 && u > 0.05 ? 0.006 * (u - 0.05) / 0.25 : 0.0;
    };
    const BlockFeatures f = extract_block_features(box_mesh({1.0, 0.6, 0.5}, 0.005, erosion), {});
    ASSERT_EQ(f.status, BlockStatus::kOk) << f.message;
    const PlanarFace* facade = face_along(f, Eigen::Vector3d::UnitX());
    ASSERT_NE(facade, nullptr);
    const double angle_deg =
        std::acos(std::min(1.0, facade->normal.dot(Eigen::Vector3d::UnitX()))) * 180 /
        std::numbers::pi;
    EXPECT_LT(angle_deg, 0.02);
    EXPECT_NEAR(facade->offset_m, 0.5, 2e-4);
}

TEST(BlockFeatures, RoughnessOrdersFinishes) {
    // +x rough (3 mm pits), -x medium (1 mm), the rest smooth.
    const Relief relief = [](int face, double u, double v) {
        const double amplitude = face == 0 ? 0.003 : (face == 1 ? 0.001 : 0.0);
        return amplitude * (0.5 + 0.25 * std::sin(u * 400.0) + 0.25 * std::sin(v * 330.0));
    };
    const BlockFeatures f = extract_block_features(box_mesh({0.8, 0.6, 0.5}, 0.005, relief), {});
    ASSERT_EQ(f.status, BlockStatus::kOk) << f.message;
    const PlanarFace* rough = face_along(f, Eigen::Vector3d::UnitX());
    const PlanarFace* medium = face_along(f, -Eigen::Vector3d::UnitX());
    const PlanarFace* smooth = face_along(f, Eigen::Vector3d::UnitY());
    ASSERT_TRUE(rough && medium && smooth);
    EXPECT_GT(rough->roughness_per_m2, medium->roughness_per_m2);
    EXPECT_GT(medium->roughness_per_m2, 2.0 * smooth->roughness_per_m2);
}

TEST(BlockFeatures, BadInputsHaveAStatus) {
    EXPECT_EQ(extract_block_features(Mesh{}, {}).status, BlockStatus::kEmpty);
    PointCloud no_normals;
    no_normals.positions.assign(100, Eigen::Vector3f::Zero());
    EXPECT_EQ(extract_block_features(no_normals, {}).status, BlockStatus::kNoNormals);
    Mesh bad = box_mesh({0.5, 0.5, 0.5}, 0.05);
    bad.triangles.emplace_back(0, 1, int(bad.vertices.size()) + 3);
    EXPECT_EQ(extract_block_features(bad, {}).status, BlockStatus::kBadMesh);
    Mesh non_manifold = box_mesh({0.6, 0.5, 0.4}, 0.01);
    non_manifold.triangles.push_back(non_manifold.triangles.front());
    const BlockFeatures nm = extract_block_features(non_manifold, {});
    EXPECT_EQ(nm.status, BlockStatus::kNonManifold) << nm.message;
    EXPECT_TRUE(nm.matchable());  // Flagged, still usable.
}

TEST(BlockFeatures, HeavyNoiseIsNotMatched) {
    Mesh noisy = box_mesh({0.8, 0.6, 0.5}, 0.01);
    std::mt19937 rng(3);
    std::normal_distribution<float> noise(0.0f, 0.01f);  // 1 cm on a 1 cm grid.
    for (Eigen::Vector3f& p : noisy.vertices.positions)
        p += Eigen::Vector3f(noise(rng), noise(rng), noise(rng));
    const BlockFeatures f = extract_block_features(noisy, {});
    EXPECT_FALSE(f.matchable()) << to_string(f.status) << ": " << f.message;
}

// A column drum: the mantle of a cylinder of radius 0.4 m and 0.8 m high about z, sampled
// every 5 mm, outward normals; with its two flat beds when `beds`.
PointCloud column_drum(bool beds) {
    constexpr double kRadius = 0.4, kHalfHeight = 0.4, kStep = 0.005;
    PointCloud cloud;
    auto add = [&](const Eigen::Vector3d& p, const Eigen::Vector3d& n) {
        cloud.positions.push_back(p.cast<float>());
        cloud.normals.push_back(n.cast<float>());
    };
    const int around = int(std::round(2.0 * std::numbers::pi * kRadius / kStep));
    for (int i = 0; i < around; ++i) {
        const double a = 2.0 * std::numbers::pi * i / around;
        const Eigen::Vector3d n(std::cos(a), std::sin(a), 0.0);
        for (double z = -kHalfHeight; z <= kHalfHeight; z += kStep)
            add(kRadius * n + Eigen::Vector3d(0, 0, z), n);
    }
    if (beds)
        for (double x = -kRadius; x <= kRadius; x += kStep)
            for (double y = -kRadius; y <= kRadius; y += kStep)
                if (x * x + y * y < kRadius * kRadius)
                    for (double sign : {1.0, -1.0}) add({x, y, sign * kHalfHeight}, {0, 0, sign});
    return cloud;
}

TEST(BlockFeatures, AColumnDrumIsNotMatchedByItsMantle) {
    // The mantle is no face: narrow strips of it fit a plane within the tolerance.
    const BlockFeatures mantle = extract_block_features(column_drum(false), {});
    EXPECT_EQ(mantle.status, BlockStatus::kNoPlanarFace) << mantle.message;
    EXPECT_FALSE(mantle.matchable());
    // With its beds: two parallel faces that never meet, nothing to match them by.
    const BlockFeatures drum = extract_block_features(column_drum(true), {});
    EXPECT_EQ(drum.status, BlockStatus::kTooFewFaces) << drum.message;
    EXPECT_FALSE(drum.matchable());
}

}  // namespace
}  // namespace anascan::reassembly
