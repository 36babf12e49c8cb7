#pragma once
// Assembly problems on the simulated monument for the tests and the figures tool: the
// chosen blocks' meshes in their fallen poses (the model frames a user has after scanning),
// their features, the true joints among them as matching face pairs, the façades of joined
// blocks and the beds of same-course neighbours as co-planar pairs, and the façade-top
// edges of same-course neighbours as co-linear pairs. Faces are named by the truth only to
// build the expert's pairs; the assembly itself sees the fallen meshes.
#include <Eigen/Geometry>
#include <random>
#include <string>
#include <vector>

#include "anascan/processing/reassembly/assembly_check.hpp"
#include "anascan/processing/reassembly/block_assembly.hpp"
#include "anascan/sim/monument.hpp"

namespace anascan::sim::testing {

namespace ra = anascan::reassembly;

struct MonumentAssembly {
    Monument monument;
    std::vector<int> index;  ///< Monument block of each problem block.
    ra::AssemblyProblem problem;
    std::vector<Pose> truth;  ///< T_monument_model per problem block.
};

// The detected face of a block whose normal is the block axis `face` (within 5 degrees).
inline int detected_face(const ra::AssemblyBlock& b, const MonumentBlock& mb, BlockFace face) {
    const Eigen::Vector3d n = mb.T_ground_block.linear() * face_normal(face);
    for (const ra::PlanarFace& f : b.features.faces)
        if (f.normal.dot(n) > std::cos(5.0 * M_PI / 180.0)) return f.id;
    return -1;
}

inline void add_links(MonumentAssembly& m) {
    auto ref = [&](int i, BlockFace f) {
        return ra::FaceRef{
            i, detected_face(m.problem.blocks[std::size_t(i)],
                             m.monument.blocks[std::size_t(m.index[std::size_t(i)])], f)};
    };
    for (const JointPair& j : m.monument.joints) {
        const auto ia = std::find(m.index.begin(), m.index.end(), j.a.block);
        const auto ib = std::find(m.index.begin(), m.index.end(), j.b.block);
        if (ia == m.index.end() || ib == m.index.end()) continue;
        const int a = int(ia - m.index.begin()), b = int(ib - m.index.begin());
        m.problem.contacts.push_back({ref(a, j.a.face), ref(b, j.b.face)});
        m.problem.coplanar.push_back({ref(a, BlockFace::kPosY), ref(b, BlockFace::kPosY)});
        if (j.kind != JointKind::kVertical) continue;
        m.problem.coplanar.push_back({ref(a, BlockFace::kPosZ), ref(b, BlockFace::kPosZ)});
        m.problem.coplanar.push_back({ref(a, BlockFace::kNegZ), ref(b, BlockFace::kNegZ)});
        const ra::FaceRef fa = ref(a, BlockFace::kPosY), ta = ref(a, BlockFace::kPosZ);
        const ra::FaceRef fb = ref(b, BlockFace::kPosY), tb = ref(b, BlockFace::kPosZ);
        m.problem.colinear.push_back({{a, fa.face, ta.face}, {b, fb.face, tb.face}});
    }
    // The wall's end faces are flush: the -x faces of the blocks that start a course.
    std::vector<int> starts;
    for (std::size_t i = 0; i < m.index.size(); ++i) {
        const MonumentBlock& mb = m.monument.blocks[std::size_t(m.index[i])];
        if (std::abs(
                (mb.T_monument_block * Eigen::Vector3d(-0.5 * mb.config.size_m.x(), 0, 0)).x()) <
            1e-6)
            starts.push_back(int(i));
    }
    for (std::size_t i = 1; i < starts.size(); ++i)
        m.problem.coplanar.push_back(
            {ref(starts[0], BlockFace::kNegX), ref(starts[i], BlockFace::kNegX)});
}

/// The named section's blocks `ids` (the first one fixed), meshes on a `step_m` grid.
/// `flat_joints`: the vertical joint faces without anathyrosis (no recessed centre), so
/// that they carry little geometry beyond their fine tool marks.
inline Expected<MonumentAssembly> monument_assembly(const std::string& section, std::uint64_t seed,
                                                    const std::vector<std::string>& ids,
                                                    double step_m, bool flat_joints = false) {
    auto config = named_monument(section, seed);
    if (!config) return Unexpected(config.error());
    config->grid_step_m = step_m;
    auto monument = make_monument(*config);
    if (!monument) return Unexpected(monument.error());
    MonumentAssembly m{.monument = std::move(*monument)};
    for (const std::string& id : ids)
        for (std::size_t b = 0; b < m.monument.blocks.size(); ++b) {
            MonumentBlock& mb = m.monument.blocks[b];
            if (mb.id != id) continue;
            if (flat_joints)
                for (BlockFace f : {BlockFace::kPosX, BlockFace::kNegX})
                    mb.config.finishes[std::size_t(f)].recess_m = 0.0;
            m.index.push_back(int(b));
            m.problem.blocks.push_back(
                ra::assembly_block(id, transformed_mesh(block_mesh(mb), mb.T_ground_block)));
            m.truth.push_back(mb.T_monument_block * mb.T_ground_block.inverse());
        }
    if (m.index.size() != ids.size()) return fail(ErrorCode::kInvalidArgument, "unknown block id");
    m.problem.fixed = {0};
    add_links(m);
    return m;
}

/// Rotation (degrees) and centroid displacement (metres) of block b relative to block 0.
struct BlockError {
    double rotation_deg = 0.0, translation_m = 0.0;
};
inline BlockError block_error(const MonumentAssembly& m, const std::vector<Pose>& T,
                              std::size_t b) {
    const Pose truth_rel = m.truth[0].inverse() * m.truth[b];
    const Pose rel = T[0].inverse() * T[b];
    const Pose E = truth_rel.inverse() * rel;
    Eigen::Vector3d c = Eigen::Vector3d::Zero();
    for (const auto& x : m.problem.blocks[b].points.positions) c += x.cast<double>();
    c /= double(std::max<std::size_t>(1, m.problem.blocks[b].points.size()));
    return {rotation_angle_deg(E), (E * c - c).norm()};
}

/// The truth with every block but the first moved by `angle_deg` about a random axis
/// through its centroid and `shift_m` in a random direction.
inline std::vector<Pose> perturbed_truth(const MonumentAssembly& m, double angle_deg,
                                         double shift_m, unsigned seed) {
    std::mt19937 rng(seed);
    std::normal_distribution<double> N(0.0, 1.0);
    std::vector<Pose> T = m.truth;
    for (std::size_t b = 1; b < T.size(); ++b) {
        Eigen::Vector3d c = Eigen::Vector3d::Zero();
        for (const auto& x : m.problem.blocks[b].points.positions) c += x.cast<double>();
        c = T[b] * (c / double(m.problem.blocks[b].points.size()));
        const Eigen::Vector3d axis = Eigen::Vector3d(N(rng), N(rng), N(rng)).normalized();
        const Eigen::Vector3d dir = Eigen::Vector3d(N(rng), N(rng), N(rng)).normalized();
        T[b] = Eigen::Translation3d(c + shift_m * dir) *
               Eigen::AngleAxisd(angle_deg * M_PI / 180.0, axis) * Eigen::Translation3d(-c) * T[b];
    }
    return T;
}

}  // namespace anascan::sim::testing
