#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <cmath>
#include <map>
#include <set>
#include <string>

#include "anascan/sim/ray_caster.hpp"
#include "anascan/sim/scene.hpp"
#include "sim_test_scenes.hpp"

namespace anascan::sim {
namespace {

StoneBlockConfig coarse_block() { return StoneBlockConfig{.grid_step_m = 0.005}; }

// Signed volume by the divergence theorem (positive for outward triangles).
double volume(const Mesh& mesh) {
    double v = 0.0;
    for (const Eigen::Vector3i& t : mesh.triangles) {
        const Eigen::Vector3d a = mesh.vertices.positions[t[0]].cast<double>();
        v += a.dot(mesh.vertices.positions[t[1]].cast<double>().cross(
                 mesh.vertices.positions[t[2]].cast<double>())) /
             6.0;
    }
    return v;
}

TEST(StoneBlock, IsAClosedOutwardOrientedMesh) {
    const StoneBlockConfig config = coarse_block();
    const Mesh mesh = make_stone_block(config);
    std::map<std::pair<int, int>, int> directed;
    for (const Eigen::Vector3i& t : mesh.triangles)
        for (int k = 0; k < 3; ++k) ++directed[{t[k], t[(k + 1) % 3]}];
    for (const auto& [edge, count] : directed) {
        ASSERT_EQ(count, 1) << "edge " << edge.first << "-" << edge.second;
        ASSERT_EQ(directed.count({edge.second, edge.first}), 1u) << "open edge";
    }
    const double box = config.size_m.prod();
    EXPECT_GT(volume(mesh), 0.97 * box);  // Holes, ornament and chips remove a little.
    EXPECT_LT(volume(mesh), box);
    EXPECT_EQ(mesh.vertices.normals.size(), mesh.vertices.size());
}

TEST(StoneBlock, SameSeedSameMeshOtherSeedOtherFeatures) {
    StoneBlockConfig config = coarse_block();
    const Mesh a = make_stone_block(config), b = make_stone_block(config);
    EXPECT_EQ(a.vertices.positions, b.vertices.positions);
    EXPECT_EQ(a.triangles, b.triangles);
    config.seed = 77;
    EXPECT_NE(make_stone_block(config).vertices.positions, a.vertices.positions);
}

// Depth below the face plane where a ray along -n at (u, v) of the face meets the block.
double depth_at(const RayCaster& caster, const Eigen::Vector3d& surface_point,
                const Eigen::Vector3d& n) {
    const auto hit = caster.cast(surface_point + n, -n);
    return hit ? hit->distance_m - 1.0 : NAN;
}

TEST(StoneBlock, HasTheConfiguredHolesAndOrnament) {
    const StoneBlockConfig config = coarse_block();
    const RayCaster caster = testing::caster_of(make_stone_block(config));
    const Eigen::Vector3d half = 0.5 * config.size_m;
    const Eigen::Vector3d up = Eigen::Vector3d::UnitZ();
    // The top dowel hole at x = -0.15 m; the bottom one at y = 0.1 m (-z face axes: y, x).
    EXPECT_NEAR(depth_at(caster, {-0.15, 0.0, half.z()}, up), 0.05, 0.002);
    EXPECT_NEAR(depth_at(caster, {0.0, 0.1, -half.z()}, -up), 0.05, 0.002);
    // A clamp pocket near the +x edge, and its channel.
    const double pocket_x = half.x() - 0.5 * config.margin_m - 0.0125;
    EXPECT_NEAR(depth_at(caster, {pocket_x, 0.0, half.z()}, up), 0.05, 0.002);
    EXPECT_NEAR(depth_at(caster, {pocket_x - 0.07, 0.0, half.z()}, up), 0.02, 0.002);
    // The ornament band on +y: carved background between eggs, an egg's crest at full height.
    const double band_z = half.z() - config.ornament.top_offset_m - 0.5 * config.ornament.height_m;
    const Eigen::Vector3d y = Eigen::Vector3d::UnitY();
    EXPECT_NEAR(depth_at(caster, {0.0, half.y(), band_z}, y), config.ornament.depth_m, 0.002);
    EXPECT_NEAR(depth_at(caster, {0.5 * config.ornament.period_m, half.y(), band_z}, y), 0.0,
                0.002);
    // Outside every feature the dressed surface lies within its finish amplitude.
    EXPECT_LT(depth_at(caster, {0.3, 0.1, half.z()}, up), 0.0011);
}

// RMS depth of the face below its plane over the face's central part (no holes there).
double face_roughness(const RayCaster& caster, const Eigen::Vector3d& half, BlockFace face) {
    const Eigen::Vector3d n = face_normal(face);
    Eigen::Vector3d a = n.cross(Eigen::Vector3d::UnitZ());
    if (a.norm() < 0.5) a = Eigen::Vector3d::UnitX();
    const Eigen::Vector3d b = n.cross(a.normalized());
    double sum2 = 0.0;
    int count = 0;
    for (int i = -10; i <= 10; ++i) {
        for (int j = -3; j <= 3; ++j) {
            const Eigen::Vector3d p = n.cwiseAbs().cwiseProduct(half).norm() * n +
                                      0.01 * i * a.normalized() + 0.006 * j * b;
            const double d = depth_at(caster, p, n);
            sum2 += d * d;
            ++count;
        }
    }
    return std::sqrt(sum2 / count);
}

TEST(StoneBlock, FacesHaveTheirOwnRoughness) {
    StoneBlockConfig config = coarse_block();
    config.grid_step_m = 0.002;
    config.size_m = {0.5, 0.4, 0.3};
    config.chip_count = 0;
    config.ornament.enabled = false;
    const RayCaster caster = testing::caster_of(make_stone_block(config));
    const Eigen::Vector3d half = 0.5 * config.size_m;
    const double fine = face_roughness(caster, half, BlockFace::kPosX);     // 0.3 mm marks.
    const double pointed = face_roughness(caster, half, BlockFace::kNegY);  // 3 mm marks.
    const double rough = face_roughness(caster, half, BlockFace::kNegZ);    // 6 mm marks.
    EXPECT_LT(fine, 0.0004);
    EXPECT_GT(pointed, 3.0 * fine);
    EXPECT_GT(rough, 1.5 * pointed);
}

TEST(Scene, BlockRestsOnTheGroundAndCanBeTurnedOver) {
    const Scene upright = testing::small_scene();
    const Mesh stone = surface_mesh(upright, SurfaceKind::kStone);
    float min_z = INFINITY;
    for (std::size_t i = 0; i < stone.vertices.size(); ++i)
        min_z = std::min(min_z, static_cast<float>(stone.vertices.world_position(i).z()));
    EXPECT_GE(min_z, -1e-6f);
    EXPECT_LT(min_z, 1e-3f);
    EXPECT_GT(upright.T_world_block.linear()(2, 2), 0.99);
    SceneConfig turned = named_scene("small-block-turned").value();
    turned.block.grid_step_m = 0.004;
    const Scene scene = make_scene(turned);
    EXPECT_LT(scene.T_world_block.linear()(2, 2), -0.99);  // Block z points down.
    EXPECT_NEAR(scene.T_world_block.translation().z(), 0.5 * turned.block.size_m.z(), 1e-12);
    // The same block: identical vertices up to the pose change.
    const Mesh a = surface_mesh(upright, SurfaceKind::kStone);
    const Mesh b = surface_mesh(scene, SurfaceKind::kStone);
    ASSERT_EQ(a.vertices.size(), b.vertices.size());
    const Pose T_b_a = scene.T_world_block * upright.T_world_block.inverse();
    for (std::size_t i = 0; i < a.vertices.size(); i += 97)
        ASSERT_LT((T_b_a * a.vertices.world_position(i) - b.vertices.world_position(i)).norm(),
                  1e-6);
}

TEST(Scene, HasGroundAndTentAndOneKindPerTriangle) {
    const Scene scene = testing::small_scene();
    ASSERT_EQ(scene.triangle_kinds.size(), scene.mesh.triangles.size());
    EXPECT_GT(surface_mesh(scene, SurfaceKind::kGround).triangles.size(), 0u);
    EXPECT_GT(surface_mesh(scene, SurfaceKind::kTent).triangles.size(), 0u);
    EXPECT_EQ(triangle_albedos(scene).size(), scene.mesh.triangles.size());
    // From inside the tent every horizontal direction hits a wall.
    const RayCaster caster = testing::caster_of(scene.mesh);
    for (int k = 0; k < 8; ++k) {
        const double a = k * 0.785;
        EXPECT_TRUE(caster.cast({2.0, 0.0, 1.5}, {std::cos(a), std::sin(a), 0.0}).has_value());
    }
}

TEST(Scene, CatalogueNamesResolveAndUnknownNamesAreRejected) {
    for (const SceneInfo& info : scene_catalog()) {
        if (info.name == "random-block:SEED") continue;  // RandomBlocksAreDrawnFromTheirSeed.
        const auto config = named_scene(info.name);
        ASSERT_TRUE(config.has_value()) << info.name;
        EXPECT_GE(config->block.size_m.maxCoeff(), 0.4);
        EXPECT_LE(config->block.size_m.maxCoeff(), 1.5);
    }
    const auto unknown = named_scene("pyramid");
    ASSERT_FALSE(unknown.has_value());
    EXPECT_EQ(unknown.error().code, ErrorCode::kInvalidArgument);
    EXPECT_NE(unknown.error().message.find("octagon-block"), std::string::npos);
}

TEST(Scene, RandomBlocksAreDrawnFromTheirSeed) {
    std::set<long> lengths_mm;
    for (int seed = 0; seed < 50; ++seed) {
        const auto config = named_scene("random-block:" + std::to_string(seed));
        ASSERT_TRUE(config.has_value()) << seed;
        const Eigen::Vector3d size = config->block.size_m;
        EXPECT_GE(size.minCoeff(), 0.4) << seed;
        EXPECT_LE(size.maxCoeff(), 1.5) << seed;
        EXPECT_LE(size.z(), size.y()) << seed;
        EXPECT_LE(size.y(), size.x()) << seed;
        lengths_mm.insert(std::lround(size.x() * 1e3));
        const auto again = named_scene("random-block:" + std::to_string(seed));
        EXPECT_EQ(again->block.size_m, size);
        EXPECT_EQ(again->placement.yaw_deg, config->placement.yaw_deg);
    }
    EXPECT_GT(lengths_mm.size(), 40u);  // Drawn, not a few fixed sizes.
    const Scene scene = make_scene(named_scene("random-block:1").value());
    EXPECT_GT(scene.mesh.triangles.size(), 1000u);
    for (const char* bad : {"random-block:", "random-block:x", "random-block:-3"}) {
        const auto rejected = named_scene(bad);
        ASSERT_FALSE(rejected.has_value()) << bad;
        EXPECT_NE(rejected.error().message.find("random-block:SEED"), std::string::npos);
    }
}

}  // namespace
}  // namespace anascan::sim
