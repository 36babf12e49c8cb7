#pragma once
/// \file
/// Verification of a block assembly on the dense models, not only on the constraint
/// samples: the penetration depth by signed distance between the placed blocks, the gap
/// distribution on every matching face pair, the angle and offset of each co-planar face
/// pair and the angle and distance of each co-linear line pair.
///
/// Signed distance of a point x of one block to another block's triangle mesh, signed by
/// the angle-weighted pseudo-normal of the closest feature (negative inside; a closest
/// feature on an open mesh's rim counts as outside). A block without triangles is signed
/// by its vertex normals: inside when both the nearest vertex and the median over the 9
/// nearest say so, at most as deep as the nearest vertex is far.
/// Only points within `near_m` of the other block's surface are measured: a point deeper
/// inside than that is not counted (penetrations beyond a few centimetres are gross
/// misplacements that the pose errors show).
///
/// Pure geometry: no I/O, no logging, no threads.

#include <string>
#include <vector>

#include "anascan/processing/reassembly/block_assembly.hpp"

namespace anascan::reassembly {

struct ContactCheck {
    std::string pair;
    std::size_t points = 0;  ///< Points of both faces in front of the partner face.
    double gap_median_m = 0.0, gap_p95_m = 0.0, gap_max_m = 0.0;
    double gap_min_m = 0.0;  ///< Negative: the deepest penetration on this pair.
};

struct CoplanarCheck {
    std::string pair;
    double angle_deg = 0.0;
    double offset_m = 0.0;  ///< Mean distance of each face's centre to the other's plane.
};

struct ColinearCheck {
    std::string pair;
    double angle_deg = 0.0;
    double distance_m = 0.0;  ///< Largest distance of a line's samples to the other line.
};

struct AssemblyCheck {
    double penetration_max_m = 0.0;   ///< Deepest point of any block inside another.
    double penetration_mean_m = 0.0;  ///< Mean depth over the penetrating points.
    std::size_t penetrating_points = 0;
    std::size_t measured_points = 0;
    std::vector<ContactCheck> contacts;
    /// Per block and model point: its deepest penetration into another block (0 outside).
    std::vector<std::vector<float>> depth_m;
    /// Per block and model point of a matching face: its gap to the partner block (signed,
    /// negative inside), NaN for the other points.
    std::vector<std::vector<float>> gap_m;
    std::vector<CoplanarCheck> coplanar;
    std::vector<ColinearCheck> colinear;
};

struct CheckConfig {
    double near_m = 0.03;          ///< Points this close to another block are measured.
    int sign_neighbours = 9;       ///< Nearest vertices whose median gives the sign.
    double gate_m = 0.01;          ///< Contact points further along the face are not in front.
    double tolerance_m = 0.00005;  ///< Depths below this are contact, not penetration.
    int line_samples = 5;
};

/// Co-planar and co-linear measures only (cheap; used by assemble_blocks).
void check_links(const AssemblyProblem& problem, const std::vector<Pose>& T,
                 const CheckConfig& config, AssemblyCheck& out);

/// Everything above on the dense models.
AssemblyCheck check_assembly(const AssemblyProblem& problem, const std::vector<Pose>& T,
                             const CheckConfig& config = {});

}  // namespace anascan::reassembly
