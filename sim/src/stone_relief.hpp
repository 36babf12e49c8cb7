#pragma once
// Depth of the dressed surface below each face plane of a stone block: tool marks, drafted
// margins, clamp and dowel holes, the ornament band. Internal to make_stone_block.

#include <Eigen/Core>

#include "anascan/sim/stone_block.hpp"

namespace anascan::sim::detail {

/// A face of the centred block: outward normal n and in-face axes a, b with a x b = n.
struct FaceFrame {
    BlockFace face = BlockFace::kPosX;
    Eigen::Vector3d n, a, b;
    double half_a_m = 0.0, half_b_m = 0.0, half_n_m = 0.0;  ///< Half extents along a, b, n.
};

FaceFrame face_frame(BlockFace face, const Eigen::Vector3d& half_m);

/// Depth (metres, >= 0) of the surface below the face plane at face coordinates (u, v)
/// (metres from the face centre along a and b).
double face_relief_m(const StoneBlockConfig& config, const FaceFrame& frame, double u, double v);

}  // namespace anascan::sim::detail
