#pragma once
/// \file
/// Simulation scenes: a procedural stone block lying on the ground of a scanning tent, in
/// the world frame (metres, z up, ground at z = 0), with its ground-truth mesh.

#include <cstdint>
#include <string>
#include <string_view>
#include <vector>

#include "anascan/processing/core/expected.hpp"
#include "anascan/processing/core/mesh.hpp"
#include "anascan/processing/core/pose.hpp"
#include "anascan/sim/stone_block.hpp"

namespace anascan::sim {

/// What a triangle of a scene belongs to (decides its albedo).
enum class SurfaceKind : std::uint8_t { kStone, kGround, kTent };

/// Diffuse reflectance of a surface kind, 0..1.
double albedo(SurfaceKind kind);

/// How the block lies: which face rests on the ground (kPosZ = turned over), turned about
/// the vertical by yaw, centred above position_m.
struct BlockPlacement {
    BlockFace resting_face = BlockFace::kNegZ;
    double yaw_deg = 0.0;
    Eigen::Vector2d position_m = Eigen::Vector2d::Zero();  ///< World x, y of the block centre.
};

struct SceneConfig {
    std::string name = "custom";
    StoneBlockConfig block;
    BlockPlacement placement;
    Eigen::Vector3d tent_size_m{8.0, 8.0, 3.0};  ///< Floor x, y and height; centred at 0.
    bool with_tent = true;                       ///< Walls and roof around the ground.
};

/// A scene's triangles (world frame) with the kind of each, and where the block lies.
struct Scene {
    std::string name;
    Mesh mesh;                                ///< Block, ground, tent; world frame.
    std::vector<SurfaceKind> triangle_kinds;  ///< One per triangle of `mesh`.
    Pose T_world_block = Pose::Identity();    ///< Block frame (centred) in the world.
    Eigen::Vector3d block_size_m = Eigen::Vector3d::Zero();
};

/// Builds a scene; the same config always gives the identical mesh.
Scene make_scene(const SceneConfig& config);

/// The pose that rests `placement.resting_face` on the ground (z = 0) for a block of size.
Pose block_pose(const BlockPlacement& placement, const Eigen::Vector3d& size_m);

/// Albedo of every triangle of the scene (for the scanners' intensities).
std::vector<float> triangle_albedos(const Scene& scene);

/// Only the triangles of one kind (e.g. the stone, for accuracy checks), world frame.
Mesh surface_mesh(const Scene& scene, SurfaceKind kind);

/// Names of the predefined scenes, with a one-line description each.
struct SceneInfo {
    std::string name;
    std::string description;
};
std::vector<SceneInfo> scene_catalog();

/// The config of a predefined scene; kInvalidArgument naming the known scenes otherwise.
Expected<SceneConfig> named_scene(std::string_view name);

}  // namespace anascan::sim
