#pragma once
/// \file
/// A simulated monument with ground truth (method paper §5): a wall section built as
/// courses of ashlar blocks whose features cross the joints (a moulding and an ornament
/// band along the façade, Π-clamp channels half in each block across vertical joints,
/// dowel holes meeting across bed joints, anathyrosis on the joint faces, a smooth façade
/// and rough hidden faces), then weathered and laid on the ground in fallen poses.
///
/// Frames: the monument frame has the wall along +x, the façade facing +y, z up, the
/// foot of the wall at z = 0. Each block frame is centred (make_stone_block); its +y face
/// is the façade, ±x the vertical joint faces, ±z the bed faces, -y the back.

#include <cstdint>
#include <string>
#include <string_view>
#include <vector>

#include "anascan/processing/core/expected.hpp"
#include "anascan/processing/core/mesh.hpp"
#include "anascan/processing/core/pose.hpp"
#include "anascan/sim/stone_block.hpp"

namespace anascan::sim {

/// Weathering after the fall: chips along edges, lost corners, erosion everywhere.
struct WeatheringConfig {
    int max_chips = 6;                  ///< Chips per block: uniform in [0, max_chips].
    double chip_max_depth_m = 0.02;     ///< Largest chip depth.
    double lost_corner_share = 0.25;    ///< Share of blocks that lost one corner.
    double lost_corner_depth_m = 0.06;  ///< Largest corner cut along its diagonal.
    double erosion_m = 0.0005;          ///< Peak erosion depth over the surface.
};

struct MonumentConfig {
    std::string name = "custom";
    int courses = 2;
    int blocks_per_course = 6;
    double mean_block_length_m = 1.0;  ///< Each course spans blocks_per_course times this.
    double min_block_length_m = 0.5;
    double max_block_length_m = 1.4;
    double min_course_height_m = 0.4;
    double max_course_height_m = 0.6;
    double depth_m = 0.6;               ///< Wall thickness (y extent of every block).
    double min_joint_stagger_m = 0.15;  ///< Vertical joints of successive courses differ so.
    double grid_step_m = 0.005;         ///< Mesh vertex spacing (make_stone_block).
    double ground_spacing_m = 2.5;      ///< Spacing of the fallen blocks on the ground grid.
    WeatheringConfig weathering;
    std::uint64_t seed = 1;
};

/// One face of one block of the monument.
struct BlockFaceRef {
    int block = 0;  ///< Index into Monument::blocks.
    BlockFace face = BlockFace::kPosX;
};

enum class JointKind { kVertical, kBed };

/// Two faces that touched in the built monument.
struct JointPair {
    BlockFaceRef a, b;
    JointKind kind = JointKind::kVertical;
};

struct MonumentBlock {
    std::string id;  ///< "c0b3": course 0, block 3 from the left.
    int course = 0;
    StoneBlockConfig config;                   ///< Geometry in the block frame.
    Pose T_monument_block = Pose::Identity();  ///< Built pose.
    Pose T_ground_block = Pose::Identity();    ///< Fallen pose on the ground (z = 0).
};

struct Monument {
    std::string name;
    std::vector<MonumentBlock> blocks;
    std::vector<JointPair> joints;  ///< Every true adjacent face pair, each once.
};

/// Builds the monument's layout and truth (no meshes); the same config gives the same one.
/// kInvalidArgument when the lengths cannot be drawn within their bounds.
Expected<Monument> make_monument(const MonumentConfig& config);

/// A block's mesh in its block frame (make_stone_block of its config).
Mesh block_mesh(const MonumentBlock& block);

/// The mesh moved by T_to_block (positions and normals).
Mesh transformed_mesh(const Mesh& mesh_block, const Pose& T_to_block);

/// "+x", "-x", "+y", "-y", "+z", "-z".
std::string_view face_name(BlockFace face);

struct MonumentInfo {
    std::string name;
    std::string description;
};
/// The named sections (octagon-base-course, octagon-wall, ...).
std::vector<MonumentInfo> monument_catalog();

/// The config of a named section with the given seed (0: the section's own seed);
/// kInvalidArgument naming the known sections otherwise.
Expected<MonumentConfig> named_monument(std::string_view name, std::uint64_t seed = 0);

}  // namespace anascan::sim
