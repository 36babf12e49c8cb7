#include <gtest/gtest.h>

#include "anascan/processing/surface/mesh_distance.hpp"
#include "anascan/processing/surface/mesh_topology.hpp"
#include "anascan/processing/surface/model_report.hpp"
#include "surface_test_meshes.hpp"

namespace anascan {
namespace {

using test::cube;

TEST(MeshTopology, CubeIsClosedManifoldOneComponent) {
    const Mesh m = cube();
    const MeshTopology t = analyse_topology(m);
    EXPECT_TRUE(t.closed());
    EXPECT_TRUE(t.manifold());
    EXPECT_EQ(t.components, 1u);
    EXPECT_TRUE(t.boundary_loops.empty());
    EXPECT_NEAR(mesh_volume_m3(m), 1.0, 1e-9);
    EXPECT_NEAR(mesh_area_m2(m), 6.0, 1e-9);
    const Eigen::Vector3d box = oriented_box_mm(m);
    EXPECT_NEAR(box.x(), 1000.0, 1e-3);
    EXPECT_NEAR(box.z(), 1000.0, 1e-3);
}

TEST(MeshTopology, OpenCubeHasOneSquareLoop) {
    Mesh m = cube();
    m.triangles.resize(10);  // drop the last face
    const MeshTopology t = analyse_topology(m);
    EXPECT_FALSE(t.closed());
    EXPECT_TRUE(t.manifold());
    EXPECT_EQ(t.boundary_edges, 4u);
    ASSERT_EQ(t.boundary_loops.size(), 1u);
    EXPECT_EQ(t.boundary_loops[0].size(), 4u);
}

TEST(MeshTopology, FlippedTriangleAndThirdUseAreFound) {
    Mesh m = cube();
    std::swap(m.triangles[0][1], m.triangles[0][2]);
    EXPECT_GT(analyse_topology(m).inconsistent_edges, 0u);
    Mesh fin = cube();
    fin.vertices.positions.emplace_back(0.5f, 0.5f, 2.0f);
    fin.triangles.emplace_back(4, 5, 8);  // a fin on the top edge 4-5
    const MeshTopology t = analyse_topology(fin);
    EXPECT_EQ(t.non_manifold_edges, 1u);
    EXPECT_FALSE(t.closed());
}

TEST(MeshTopology, TwoCubesTouchingAtAVertexAreNotVertexManifold) {
    Mesh m = cube();
    const Mesh second = cube();
    const int offset = 7;  // share vertex 7 of the first as vertex 0 of the second
    for (int i = 1; i < 8; ++i) {
        m.vertices.positions.push_back(second.vertices.positions[i] + Eigen::Vector3f::Ones());
    }
    for (Eigen::Vector3i t : second.triangles) {
        for (int k = 0; k < 3; ++k) t[k] = t[k] == 0 ? offset : t[k] + offset;
        m.triangles.push_back(t);
    }
    const MeshTopology t = analyse_topology(m);
    EXPECT_EQ(t.non_manifold_vertices, 1u);
    EXPECT_EQ(t.components, 2u);  // edge-connected parts
    EXPECT_FALSE(t.manifold());
}

TEST(MeshDistance, MatchesBruteForceOnTheCube) {
    const Mesh m = cube(0.1);
    const MeshDistance d(m);
    EXPECT_NEAR(d.distance_m({0.05, 0.05, 0.3}), 0.2, 1e-7);  // float vertices
    EXPECT_NEAR(d.distance_m({0.05, 0.05, 0.05}), 0.05, 1e-7);
    EXPECT_NEAR(d.distance_m({0.2, 0.2, 0.05}), std::sqrt(0.02), 1e-7);
    const auto samples = sample_surface(m, 0.01);
    EXPECT_NEAR(double(samples.size()), 0.06 / 1e-4, 60.0);
    for (const auto& s : samples) EXPECT_LT(d.distance_m(s.position_m), 1e-6);
}

}  // namespace
}  // namespace anascan
