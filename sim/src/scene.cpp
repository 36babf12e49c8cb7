#include "anascan/sim/scene.hpp"

#include <Eigen/Geometry>
#include <cmath>
#include <numbers>

namespace anascan::sim {
namespace {

constexpr double kDegToRad = std::numbers::pi / 180.0;

// Appends `part` (vertices in the world frame) with the given kind.
void append_part(Scene& scene, const Mesh& part, SurfaceKind kind) {
    const int base = static_cast<int>(scene.mesh.vertices.size());
    append(scene.mesh.vertices, part.vertices);
    for (const Eigen::Vector3i& t : part.triangles) {
        scene.mesh.triangles.push_back(t + Eigen::Vector3i::Constant(base));
        scene.triangle_kinds.push_back(kind);
    }
}

// A planar quad (corners counter-clockwise seen from the side `normal` points to) split
// into cells of about cell_m, with vertex normals.
Mesh quad(const Eigen::Vector3d& origin, const Eigen::Vector3d& edge_u,
          const Eigen::Vector3d& edge_v, double cell_m) {
    Mesh mesh;
    const int nu = std::max(1, static_cast<int>(std::ceil(edge_u.norm() / cell_m)));
    const int nv = std::max(1, static_cast<int>(std::ceil(edge_v.norm() / cell_m)));
    const Eigen::Vector3f normal = edge_u.cross(edge_v).normalized().cast<float>();
    for (int j = 0; j <= nv; ++j) {
        for (int i = 0; i <= nu; ++i) {
            const Eigen::Vector3d p =
                origin + edge_u * (double(i) / nu) + edge_v * (double(j) / nv);
            mesh.vertices.positions.push_back(p.cast<float>());
            mesh.vertices.normals.push_back(normal);
        }
    }
    for (int j = 0; j < nv; ++j) {
        for (int i = 0; i < nu; ++i) {
            const int v00 = j * (nu + 1) + i, v10 = v00 + 1, v01 = v00 + nu + 1, v11 = v01 + 1;
            mesh.triangles.emplace_back(v00, v10, v11);
            mesh.triangles.emplace_back(v00, v11, v01);
        }
    }
    return mesh;
}

// The tent from inside: four walls and a flat roof, facing inward.
void add_tent(Scene& scene, const Eigen::Vector3d& size_m) {
    const double hx = 0.5 * size_m.x(), hy = 0.5 * size_m.y(), h = size_m.z();
    const Eigen::Vector3d up(0, 0, h);
    const double cell = 1.0;
    append_part(scene, quad({-hx, -hy, 0}, up, {2 * hx, 0, 0}, cell), SurfaceKind::kTent);
    append_part(scene, quad({hx, hy, 0}, up, {-2 * hx, 0, 0}, cell), SurfaceKind::kTent);
    append_part(scene, quad({hx, -hy, 0}, up, {0, 2 * hy, 0}, cell), SurfaceKind::kTent);
    append_part(scene, quad({-hx, hy, 0}, up, {0, -2 * hy, 0}, cell), SurfaceKind::kTent);
    append_part(scene, quad({-hx, -hy, h}, {0, 2 * hy, 0}, {2 * hx, 0, 0}, cell),
                SurfaceKind::kTent);
}

Eigen::Matrix3d resting_rotation(BlockFace face) {
    using Eigen::AngleAxisd;
    const double quarter = 0.5 * std::numbers::pi;
    switch (face) {
        case BlockFace::kNegZ:
            return Eigen::Matrix3d::Identity();
        case BlockFace::kPosZ:
            return AngleAxisd(2 * quarter, Eigen::Vector3d::UnitX()).matrix();
        case BlockFace::kPosY:
            return AngleAxisd(-quarter, Eigen::Vector3d::UnitX()).matrix();
        case BlockFace::kNegY:
            return AngleAxisd(quarter, Eigen::Vector3d::UnitX()).matrix();
        case BlockFace::kPosX:
            return AngleAxisd(quarter, Eigen::Vector3d::UnitY()).matrix();
        case BlockFace::kNegX:
            return AngleAxisd(-quarter, Eigen::Vector3d::UnitY()).matrix();
    }
    return Eigen::Matrix3d::Identity();
}

}  // namespace

double albedo(SurfaceKind kind) {
    switch (kind) {
        case SurfaceKind::kStone:
            return 0.7;  // Marble.
        case SurfaceKind::kGround:
            return 0.25;
        case SurfaceKind::kTent:
            return 0.8;
    }
    return 0.5;
}

Pose block_pose(const BlockPlacement& placement, const Eigen::Vector3d& size_m) {
    const Eigen::Matrix3d R =
        Eigen::AngleAxisd(placement.yaw_deg * kDegToRad, Eigen::Vector3d::UnitZ()).matrix() *
        resting_rotation(placement.resting_face);
    const double half_height_m = 0.5 * (R.cwiseAbs() * size_m.cwiseAbs()).z();
    Pose T_world_block = Pose::Identity();
    T_world_block.linear() = R;
    T_world_block.translation() =
        Eigen::Vector3d(placement.position_m.x(), placement.position_m.y(), half_height_m);
    return T_world_block;
}

Scene make_scene(const SceneConfig& config) {
    Scene scene{.name = config.name, .block_size_m = config.block.size_m.cwiseAbs()};
    scene.T_world_block = block_pose(config.placement, scene.block_size_m);
    Mesh block = make_stone_block(config.block);
    // World coordinates in the positions themselves (origin 0), so that the exported PLY
    // is in the world frame for every viewer.
    for (Eigen::Vector3f& p : block.vertices.positions)
        p = (scene.T_world_block * p.cast<double>()).cast<float>();
    for (Eigen::Vector3f& n : block.vertices.normals)
        n = (scene.T_world_block.linear() * n.cast<double>()).cast<float>();
    append_part(scene, block, SurfaceKind::kStone);
    const double hx = 0.5 * config.tent_size_m.x(), hy = 0.5 * config.tent_size_m.y();
    append_part(scene, quad({-hx, -hy, 0}, {2 * hx, 0, 0}, {0, 2 * hy, 0}, 0.5),
                SurfaceKind::kGround);
    if (config.with_tent) add_tent(scene, config.tent_size_m);
    return scene;
}

std::vector<float> triangle_albedos(const Scene& scene) {
    std::vector<float> albedos(scene.triangle_kinds.size());
    for (std::size_t t = 0; t < albedos.size(); ++t)
        albedos[t] = static_cast<float>(albedo(scene.triangle_kinds[t]));
    return albedos;
}

Mesh surface_mesh(const Scene& scene, SurfaceKind kind) {
    Mesh out;
    std::vector<int> new_index(scene.mesh.vertices.size(), -1);
    for (std::size_t t = 0; t < scene.mesh.triangles.size(); ++t) {
        if (scene.triangle_kinds[t] != kind) continue;
        Eigen::Vector3i tri;
        for (int k = 0; k < 3; ++k) {
            int& id = new_index[scene.mesh.triangles[t][k]];
            if (id < 0) {
                id = static_cast<int>(out.vertices.positions.size());
                out.vertices.positions.push_back(
                    scene.mesh.vertices.positions[scene.mesh.triangles[t][k]]);
                if (scene.mesh.vertices.has_normals())
                    out.vertices.normals.push_back(
                        scene.mesh.vertices.normals[scene.mesh.triangles[t][k]]);
            }
            tri[k] = id;
        }
        out.triangles.push_back(tri);
    }
    out.vertices.origin_m = scene.mesh.vertices.origin_m;
    return out;
}

}  // namespace anascan::sim
