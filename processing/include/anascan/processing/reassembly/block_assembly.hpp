#pragma once
/// \file
/// Penetration-free alignment of neighbouring blocks (method paper §5.3): the blocks an
/// expert says belong together are placed so that their matching faces touch without
/// interpenetrating, with the faces that should be co-planar co-planar and the lines that
/// should be co-linear co-linear, all blocks at once and one (or more) fixed.
///
/// 1. Initial placement: Horn's closed-form absolute orientation (Eigen's umeyama without
///    scaling) from six points per matched face: the barycentre ± 0.5·n, ± 0.5·m and
///    ± 0.5·(n × m), m the in-plane part of the normal of the neighbouring face most likely
///    co-planar with its counterpart (a given co-planar pair, else the most similar
///    roughness), mapped onto the partner face with its normal reversed.
/// 2. Every iteration linearises each block's motion as a velocity field v_j(x) = c̄_j +
///    c_j × x (v_jk = v_j - v_k between blocks) and minimises
///    F_reg + μ_cp F_cp + μ_cl F_cl (each term a mean, so that they enter equally) subject
///    to n_iᵀ(x_i - y_i + v_jk(x_i)) >= 0 for every sample x_i of a matching face, y_i its
///    closest point on the partner face and n_i the partner's outward normal there; the
///    quadratic program is solved by constrained_lsq.hpp. Each block then moves by the
///    helical motion of its (c̄, c) (fine/helical_motion.hpp), never by the affine step.
///
/// Pure geometry: no I/O, no logging, no threads; deterministic.

#include <Eigen/Core>
#include <string>
#include <vector>

#include "anascan/processing/core/expected.hpp"
#include "anascan/processing/core/point_cloud.hpp"
#include "anascan/processing/core/pose.hpp"
#include "anascan/processing/reassembly/block_features.hpp"
#include "anascan/processing/reassembly/face_matching.hpp"

namespace anascan::reassembly {

/// A block to assemble: its dense model (positions and outward normals) in the model frame
/// and its features found on that model (`point_face` indexes `points`).
struct AssemblyBlock {
    std::string id;
    PointCloud points;
    /// The mesh's triangles on `points` (the dense check's signed distance; empty: the
    /// check signs by the vertex normals).
    std::vector<Eigen::Vector3i> triangles;
    BlockFeatures features;
};

/// A block from its mesh: the vertices with area-weighted normals, the triangles and the
/// features.
AssemblyBlock assembly_block(std::string id, const Mesh& mesh,
                             const BlockFeatureConfig& config = {});

/// The line where faces `face_a` and `face_b` of `block` meet (an edge of its features).
struct LineRef {
    int block = 0;
    int face_a = 0, face_b = 0;
};

struct FaceLink {
    FaceRef a, b;
};
struct LineLink {
    LineRef a, b;
};

/// What the expert said: matching (touching) face pairs, co-planar face pairs, co-linear
/// line pairs, and the fixed blocks (the first block when none is given).
struct AssemblyProblem {
    std::vector<AssemblyBlock> blocks;
    std::vector<FaceLink> contacts;
    std::vector<FaceLink> coplanar;
    std::vector<LineLink> colinear;
    std::vector<int> fixed;
};

/// The normal of a contact row (registration and non-penetration constraint) at the
/// closest point y of the partner face: y's outward vertex normal (the paper's), or the
/// partner face's fitted-plane normal (the default: no pull from normals leaning at edges
/// and margins; see docs/reassembly.md for what each meets).
enum class JointNormal { kVertex, kFacePlane };

struct AssemblyConfig {
    /// Outer iterations at most; the paper needs 15-20, the tests and figures end in
    /// 5-30. When reached the status is kNotConverged with the last step.
    int max_iterations = 60;
    double converged_step_m = 2e-6;  ///< Stop when no sample point moves further.
    /// NNLS iterations per QP at most; 0: nnls_iteration_cap (3 × (constraints + 1)).
    /// A QP that reaches it ends the assembly as kNotConverged, naming the iteration.
    int qp_max_iterations = 0;
    /// Added to each QP's normal matrix, relative to its largest entry: along a direction
    /// no term fixes (a joint without its façade, with face-plane rows) a step of the
    /// undamped matrix amplifies rounding into a steady drift (1.2 mm per iteration, never
    /// converging); 1e-9 stops it without changing the walls' poses (docs/reassembly.md).
    double qp_damping = 1e-9;
    int contact_samples_per_face = 400;
    int plane_samples_per_side = 5;  ///< Grid on a face's rectangle for co-planarity.
    int line_samples = 5;            ///< Points along a line for co-linearity (>= 2).
    double contact_gate_m = 0.01;    ///< Closest points further along the face are dropped.
    JointNormal joint_normal = JointNormal::kFacePlane;
    double min_face_side_m = 0.05;  ///< A face narrower than this is a sliver.
    bool non_penetration = true;
    /// Iterations without the non-penetration constraints first (from a start far off,
    /// the soft terms bring the blocks near before the constraints hold them apart).
    int free_iterations = 0;
    bool use_coplanar = true;
    bool use_colinear = true;
    double contradiction_angle_deg = 0.5;   ///< A co-planar/co-linear pair left worse is
    double contradiction_offset_m = 0.002;  ///< reported as contradictory.
};

enum class AssemblyStatus {
    kOk,
    kInfeasible,     ///< No motion keeps the matching faces penetration-free.
    kContradictory,  ///< Co-planar or co-linear pairs that cannot all hold.
    kNotConverged,
    /// The pairs leave a block free (assembly_probe.hpp): a pair whose faces do not touch,
    /// or a block that ends elsewhere, fitting as well, when restarted along its joint.
    kUnderdetermined,
};
const char* to_string(AssemblyStatus status);

/// Residuals of the three terms: RMS over their samples (metres).
struct TermResiduals {
    double registration_rms_m = 0.0;
    double coplanar_rms_m = 0.0;
    double colinear_rms_m = 0.0;
    std::size_t constraint_samples = 0;
    std::size_t active_constraints = 0;
    int qp_iterations = 0;  ///< NNLS iterations of the step's QP.
};

struct AssemblyResult {
    AssemblyStatus status = AssemblyStatus::kOk;
    std::string message;
    std::vector<Pose> T_world_block;     ///< Final poses (model frame to assembly frame).
    std::vector<TermResiduals> history;  ///< Per iteration, before its step.
    int iterations = 0;
    double last_step_m = 0.0;            ///< Largest motion of the last step (RMS radius).
    std::vector<std::string> offending;  ///< Pairs named "A:2=B:5" when not kOk.
};

/// Horn's closed-form absolute orientation: the rigid T minimising Σ ||T p_i - q_i||².
Pose absolute_orientation(const std::vector<Eigen::Vector3d>& from,
                          const std::vector<Eigen::Vector3d>& to);

/// The pose of block `link.a.block` that lays face `link.a` onto face `link.b` of the
/// placed block (pose T_world_b), by the six points of each face. `hint` (may be null) is
/// a co-planar pair between the two blocks that names the neighbours to align.
Pose place_on_face(const AssemblyProblem& problem, const FaceLink& link, const Pose& T_world_b,
                   const FaceLink* hint);

/// Checks the problem: kInvalidArgument naming the pair or block (unknown face, both faces
/// on one block, a sliver face, a block not linked to a fixed block, a line that is no edge).
Expected<void> validate_problem(const AssemblyProblem& problem, const AssemblyConfig& config);

/// Initial poses: fixed blocks at the identity, the others by place_on_face in
/// breadth-first order from the fixed blocks. The problem is validated first
/// (validate_problem's errors): faces are indices, and an unchecked one is out of bounds.
Expected<std::vector<Pose>> initial_placement(const AssemblyProblem& problem,
                                              const AssemblyConfig& config = {});

/// The constrained simultaneous registration from `initial` poses.
Expected<AssemblyResult> assemble_blocks(const AssemblyProblem& problem,
                                         const std::vector<Pose>& initial,
                                         const AssemblyConfig& config);

/// "c0b1:2=c0b2:4" for reports.
std::string link_name(const AssemblyProblem& problem, const FaceLink& link);
std::string link_name(const AssemblyProblem& problem, const LineLink& link);

}  // namespace anascan::reassembly
