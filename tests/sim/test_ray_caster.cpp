#include <gtest/gtest.h>

#include "anascan/sim/ray_caster.hpp"

namespace anascan::sim {
namespace {

// The cube [-h, h]^3 with outward counter-clockwise triangles.
Mesh cube(double h) {
    Mesh mesh;
    for (int i = 0; i < 8; ++i)
        mesh.vertices.positions.emplace_back((i & 1) ? h : -h, (i & 2) ? h : -h, (i & 4) ? h : -h);
    const int quads[6][4] = {{0, 2, 3, 1}, {4, 5, 7, 6}, {0, 1, 5, 4},
                             {2, 6, 7, 3}, {0, 4, 6, 2}, {1, 3, 7, 5}};
    for (const auto& q : quads) {
        mesh.triangles.emplace_back(q[0], q[1], q[2]);
        mesh.triangles.emplace_back(q[0], q[2], q[3]);
    }
    return mesh;
}

TEST(RayCaster, HitsAnAnalyticCubeAtTheExactDistanceWithTheOutwardNormal) {
    const RayCaster caster = RayCaster::create(cube(0.5)).value();
    EXPECT_EQ(caster.triangle_count(), 12u);
    const Eigen::Vector3d origin(0.1, -0.2, 3.0);
    const auto hit = caster.cast(origin, -Eigen::Vector3d::UnitZ());
    ASSERT_TRUE(hit.has_value());
    EXPECT_NEAR(hit->distance_m, 2.5, 1e-12);
    EXPECT_TRUE(hit->normal.isApprox(Eigen::Vector3d::UnitZ(), 1e-12));
    // An oblique ray through a corner region: the slab test gives the entry distance.
    const Eigen::Vector3d dir = Eigen::Vector3d(-1.0, -0.3, -0.2).normalized();
    const Eigen::Vector3d o2(2.0, 0.2, 0.1);
    const auto hit2 = caster.cast(o2, dir);
    ASSERT_TRUE(hit2.has_value());
    EXPECT_NEAR((o2 + hit2->distance_m * dir).x(), 0.5, 1e-9);
    EXPECT_TRUE(hit2->normal.isApprox(Eigen::Vector3d::UnitX(), 1e-12));
}

TEST(RayCaster, RespectsTheRayIntervalAndReportsOcclusion) {
    const RayCaster caster = RayCaster::create(cube(0.5)).value();
    const Eigen::Vector3d origin(0, 0, 3.0), down = -Eigen::Vector3d::UnitZ();
    EXPECT_FALSE(caster.cast(origin, down, 0.0, 2.4).has_value());
    const auto far_side = caster.cast(origin, down, 2.6);  // Starts inside the cube.
    ASSERT_TRUE(far_side.has_value());
    EXPECT_NEAR(far_side->distance_m, 3.5, 1e-12);
    EXPECT_TRUE(caster.occluded(origin, down, 0.0, 10.0));
    EXPECT_FALSE(caster.occluded(origin, down, 0.0, 2.4));
    EXPECT_FALSE(caster.cast(origin, Eigen::Vector3d::UnitZ()).has_value());
}

TEST(RayCaster, RejectsEmptyAndInvalidMeshes) {
    EXPECT_EQ(RayCaster::create(Mesh{}).error().code, ErrorCode::kEmpty);
    Mesh bad = cube(1.0);
    bad.triangles.back() = Eigen::Vector3i(0, 1, 8);
    const auto out_of_range = RayCaster::create(bad);
    ASSERT_FALSE(out_of_range.has_value());
    EXPECT_EQ(out_of_range.error().code, ErrorCode::kInvalidArgument);
    EXPECT_NE(out_of_range.error().message.find("triangle 11"), std::string::npos);
    Mesh nan = cube(1.0);
    nan.vertices.positions[3].x() = NAN;
    EXPECT_EQ(RayCaster::create(nan).error().code, ErrorCode::kInvalidArgument);
}

}  // namespace
}  // namespace anascan::sim
