#pragma once
/// \file
/// Procedural stone blocks like the Octagon's: a dressed ashlar block with planar faces of
/// different finish, clamp and dowel holes, an ornament band and chipped edges, as a closed
/// triangle mesh in the block frame (centred at the origin, x length, y width, z height).

#include <array>
#include <cstdint>
#include <vector>

#include "anascan/processing/core/mesh.hpp"

namespace anascan::sim {

/// Faces of the block, by outward normal.
enum class BlockFace { kPosX, kNegX, kPosY, kNegY, kPosZ, kNegZ };
inline constexpr int kBlockFaceCount = 6;

/// How a face was dressed: relief amplitude and wavelength of its tool marks.
struct FaceFinish {
    double amplitude_m = 0.0005;    ///< Peak depth of the tool marks below the face plane.
    double wavelength_m = 0.01;     ///< Spacing of the marks (noise scale or groove spacing).
    bool parallel_grooves = false;  ///< Claw-chisel grooves (true) or pointed/random (false).
    double groove_angle_deg = 30;   ///< Groove direction in the face, from its first axis.
    /// Anathyrosis: the rough centre sits this much below the smooth drafted margin.
    double recess_m = 0.0;
};

/// A rectangular clamp channel with deeper end pockets, cut into the top face across a
/// short edge (as the Π-clamps joining neighbouring blocks).
struct ClampHole {
    BlockFace edge_face = BlockFace::kPosX;  ///< The side face whose top edge it crosses.
    double offset_m = 0.0;                   ///< Position along that edge from its middle.
    double length_m = 0.14;                  ///< Channel length, perpendicular to the edge.
    double width_m = 0.025;
    double channel_depth_m = 0.02;
    double pocket_depth_m = 0.05;  ///< Depth of the square pockets at both ends.
    /// The channel runs out through the edge (half of a clamp shared with the neighbour
    /// across a vertical joint): one pocket inside, the other in the neighbour.
    bool open_at_edge = false;
};

/// A round dowel hole in a face.
struct DowelHole {
    BlockFace face = BlockFace::kNegZ;
    double u_m = 0.0, v_m = 0.0;  ///< Centre in the face's (first, second) axes from its middle.
    double radius_m = 0.02;
    double depth_m = 0.05;
};

/// An egg-and-dart-like relief band carved along a side face.
struct OrnamentBand {
    bool enabled = true;
    BlockFace face = BlockFace::kPosY;
    double top_offset_m = 0.04;  ///< Distance of the band's upper border below the top edge.
    double height_m = 0.08;
    double period_m = 0.06;     ///< Spacing of the eggs along the band.
    double depth_m = 0.012;     ///< Depth of the carved background.
    double phase_m = 0.0;       ///< Shift of the eggs along the band (continuity across blocks).
    bool run_to_edges = false;  ///< Through the drafted margins (a band crossing the joints).
};

/// A moulding along the top edge of a side face: a cavetto (quarter-round hollow) below a
/// flat fillet, running from edge to edge so that it continues across vertical joints.
struct Moulding {
    bool enabled = false;
    BlockFace face = BlockFace::kPosY;
    double top_offset_m = 0.02;  ///< Fillet height below the top edge.
    double height_m = 0.06;      ///< Height of the hollow below the fillet.
    double depth_m = 0.01;       ///< Deepest point of the hollow below the face plane.
};

struct StoneBlockConfig {
    Eigen::Vector3d size_m{1.2, 0.6, 0.5};  ///< Edge lengths (x, y, z), metres.
    double grid_step_m = 0.0025;            ///< Mesh vertex spacing on the faces.
    /// Finish per face in BlockFace order (+x, -x, +y, -y, +z, -z).
    std::array<FaceFinish, kBlockFaceCount> finishes{
        FaceFinish{.amplitude_m = 0.0003, .wavelength_m = 0.006},
        FaceFinish{.amplitude_m = 0.0015, .wavelength_m = 0.012, .parallel_grooves = true},
        FaceFinish{.amplitude_m = 0.0005, .wavelength_m = 0.008},
        FaceFinish{.amplitude_m = 0.003, .wavelength_m = 0.025},
        FaceFinish{.amplitude_m = 0.001,
                   .wavelength_m = 0.01,
                   .parallel_grooves = true,
                   .groove_angle_deg = 75},
        FaceFinish{.amplitude_m = 0.006, .wavelength_m = 0.05}};
    double margin_m = 0.03;  ///< Smooth drafted margin along every edge (finish fades in).
    std::vector<ClampHole> clamp_holes{ClampHole{.edge_face = BlockFace::kPosX},
                                       ClampHole{.edge_face = BlockFace::kNegX}};
    std::vector<DowelHole> dowel_holes{DowelHole{.face = BlockFace::kNegZ, .u_m = 0.1},
                                       DowelHole{.face = BlockFace::kPosZ, .u_m = -0.15}};
    OrnamentBand ornament;
    Moulding moulding;
    int chip_count = 8;                     ///< Chipped-off pieces along random edges.
    double chip_max_depth_m = 0.025;        ///< Largest chip depth, measured on the faces.
    double chip_max_half_length_m = 0.08;   ///< Largest chip half length along its edge.
    int lost_corner_count = 0;              ///< Corners broken off (weathering, falling).
    double lost_corner_max_depth_m = 0.08;  ///< Largest cut depth along the corner diagonal.
    double erosion_m = 0.0;  ///< Peak depth of weathering over the whole surface (no margin).
    std::uint64_t seed = 1;  ///< Same config and seed: identical mesh.
};

/// The block as a closed, consistently oriented (outward) mesh in the block frame, with
/// vertex normals. Holes and the ornament are skipped where they do not fit the block.
Mesh make_stone_block(const StoneBlockConfig& config);

/// Outward unit normal of a face.
Eigen::Vector3d face_normal(BlockFace face);

}  // namespace anascan::sim
