// The constrained simultaneous registration of the blocks of an assembly (paper §5.3):
// checks of the problem, then per iteration rows, the quadratic program and the helical
// motion of every free block, until no sample moves.
#include "anascan/processing/reassembly/block_assembly.hpp"

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <set>

#include "anascan/processing/reassembly/assembly_check.hpp"
#include "anascan/processing/reassembly/constrained_lsq.hpp"
#include "anascan/processing/registration/fine/helical_motion.hpp"
#include "assembly_steps.hpp"

namespace anascan::reassembly {
namespace {

using namespace assembly_detail;

Expected<void> check_face(const AssemblyProblem& p, const FaceRef& r, const AssemblyConfig& c) {
    if (r.block < 0 || std::size_t(r.block) >= p.blocks.size())
        return fail(ErrorCode::kInvalidArgument,
                    "block index " + std::to_string(r.block) + " out of range");
    const BlockFeatures& f = p.blocks[std::size_t(r.block)].features;
    const std::string name = p.blocks[std::size_t(r.block)].id + ":" + std::to_string(r.face);
    if (r.face < 0 || std::size_t(r.face) >= f.faces.size())
        return fail(ErrorCode::kInvalidArgument,
                    name + ": no such face (the block has " + std::to_string(f.faces.size()) + ")");
    const PlanarFace& face = f.faces[std::size_t(r.face)];
    if (face.height_m < c.min_face_side_m)
        return fail(ErrorCode::kInvalidArgument,
                    name + ": a sliver face (" + std::to_string(int(face.width_m * 1e3)) + " x " +
                        std::to_string(int(face.height_m * 1e3)) + " mm) cannot place a block");
    return {};
}

Expected<void> check_links(const AssemblyProblem& p, const std::vector<FaceLink>& links,
                           const AssemblyConfig& c, const char* what) {
    for (const FaceLink& l : links) {
        for (const FaceRef& r : {l.a, l.b})
            if (auto ok = check_face(p, r, c); !ok) return ok;
        if (l.a.block == l.b.block)
            return fail(ErrorCode::kInvalidArgument,
                        std::string(what) + " " + link_name(p, l) + ": both faces on one block");
    }
    return {};
}

Expected<void> check_connected(const AssemblyProblem& p) {
    std::vector<char> reached(p.blocks.size(), 0);
    for (int f : p.fixed.empty() ? std::vector<int>{0} : p.fixed) {
        if (f < 0 || std::size_t(f) >= p.blocks.size())
            return fail(ErrorCode::kInvalidArgument, "fixed block index out of range");
        reached[std::size_t(f)] = 1;
    }
    for (bool grew = true; grew;) {
        grew = false;
        for (const FaceLink& l : p.contacts)
            if (reached[std::size_t(l.a.block)] != reached[std::size_t(l.b.block)])
                reached[std::size_t(l.a.block)] = reached[std::size_t(l.b.block)] = 1, grew = true;
    }
    for (std::size_t b = 0; b < p.blocks.size(); ++b)
        if (!reached[b])
            return fail(ErrorCode::kInvalidArgument,
                        p.blocks[b].id + ": no matching face pair links it to a fixed block");
    return {};
}

double rms(const std::vector<Row>& rows) {
    double s = 0.0;
    for (const Row& r : rows) s += r.rhs * r.rhs;
    return rows.empty() ? 0.0 : std::sqrt(s / double(rows.size()));
}

// Moves every free block by the helical motion of its step; returns the largest motion of
// a point at the block's RMS radius.
double apply_step(const Eigen::VectorXd& u, const Prepared& p, const Frames& f,
                  std::vector<Pose>& T) {
    double largest = 0.0;
    for (std::size_t b = 0; b < T.size(); ++b) {
        const int s = p.slot[b];
        if (s < 0) continue;
        const Twist twist{.angular_rad = u.segment<3>(6 * s) / f.length_m[b],
                          .linear_m = u.segment<3>(6 * s + 3)};
        const Pose motion = Eigen::Translation3d(f.reference_m[b]) * helical_motion(twist) *
                            Eigen::Translation3d(-f.reference_m[b]);
        T[b] = orthonormalized(motion * T[b]);
        largest =
            std::max(largest, twist.angular_rad.norm() * f.length_m[b] + twist.linear_m.norm());
    }
    return largest;
}

// The largest motion of a block point between poses A and B (rotation at the block's RMS
// radius plus translation of its centroid).
double largest_motion(const AssemblyProblem& p, const std::vector<Pose>& A,
                      const std::vector<Pose>& B) {
    const Frames f = frames_of(p, A);
    double largest = 0.0;
    for (std::size_t b = 0; b < A.size(); ++b) {
        const Pose D = B[b] * A[b].inverse();
        const double angle = Eigen::AngleAxisd(D.linear()).angle();
        largest = std::max(
            largest, angle * f.length_m[b] + (D * f.reference_m[b] - f.reference_m[b]).norm());
    }
    return largest;
}

// The contact pairs whose constraints form the infeasibility certificate.
std::vector<std::string> offending_contacts(const AssemblyProblem& p, const std::vector<Row>& rows,
                                            const std::vector<int>& active) {
    std::set<int> links;
    for (int i : active) links.insert(rows[std::size_t(i)].link);
    std::vector<std::string> out;
    for (int l : links) out.push_back(link_name(p, p.contacts[std::size_t(l)]));
    return out;
}

// Co-planar and co-linear pairs left beyond the tolerance cannot all hold.
void flag_contradictions(const AssemblyProblem& p, const AssemblyConfig& c, AssemblyResult& out) {
    AssemblyCheck check;
    check_links(p, out.T_world_block, CheckConfig{.line_samples = c.line_samples}, check);
    for (const CoplanarCheck& cp : check.coplanar)
        if (cp.angle_deg > c.contradiction_angle_deg || cp.offset_m > c.contradiction_offset_m)
            out.offending.push_back("co-planar " + cp.pair);
    for (const ColinearCheck& cl : check.colinear)
        if (cl.angle_deg > c.contradiction_angle_deg || cl.distance_m > c.contradiction_offset_m)
            out.offending.push_back("co-linear " + cl.pair);
    if (out.offending.empty()) return;
    out.status = AssemblyStatus::kContradictory;
    out.message = "co-planar or co-linear pairs that cannot all hold";
}

// One iteration: the rows at the current poses, the QP, the helical motion. Returns the
// step; sets kInfeasible (with the offending pairs) when the constraints cannot hold.
double iterate(const AssemblyProblem& p, const Prepared& prep, const AssemblyConfig& c,
               bool constrained, AssemblyResult& out) {
    const Rows rows = build_rows(p, prep, out.T_world_block, c);
    const Frames frames = frames_of(p, out.T_world_block);
    const IterationQp q = iteration_qp(rows, prep, frames, constrained);
    const Eigen::MatrixXd& C = q.C;
    const QpResult qp = solve_constrained_normal(
        q.H(), q.g(), q.C, q.d,
        QpConfig{.damping = c.qp_damping, .max_iterations = c.qp_max_iterations});
    out.history.push_back({rms(rows.contact), rms(rows.coplanar), rms(rows.colinear),
                           std::size_t(C.rows()), qp.active.size(), qp.iterations});
    if (qp.status == QpStatus::kInfeasible) {
        out.status = AssemblyStatus::kInfeasible;
        out.offending = offending_contacts(p, rows.contact, qp.active);
        out.message = "the matching faces cannot all be made penetration-free";
        return 0.0;
    }
    if (qp.status == QpStatus::kIterationLimit) {
        out.message = "the QP of iteration " + std::to_string(out.iterations + 1) +
                      " reached its cap of " + std::to_string(qp.iterations) + " NNLS iterations";
        return -1.0;
    }
    return apply_step(qp.u, prep, frames, out.T_world_block);
}

}  // namespace

AssemblyBlock assembly_block(std::string id, const Mesh& mesh, const BlockFeatureConfig& config) {
    AssemblyBlock out{.id = std::move(id)};
    out.points.positions = mesh.vertices.positions;
    mesh_vertex_normals(mesh, out.points.normals);
    out.triangles = mesh.triangles;
    out.features = extract_block_features(mesh, config);
    return out;
}

const char* to_string(AssemblyStatus s) {
    switch (s) {
        case AssemblyStatus::kOk:
            return "ok";
        case AssemblyStatus::kInfeasible:
            return "infeasible";
        case AssemblyStatus::kContradictory:
            return "contradictory";
        case AssemblyStatus::kNotConverged:
            return "not converged";
        case AssemblyStatus::kUnderdetermined:
            return "underdetermined";
    }
    return "?";
}

Expected<void> validate_problem(const AssemblyProblem& p, const AssemblyConfig& c) {
    if (p.blocks.size() < 2)
        return fail(ErrorCode::kInvalidArgument, "an assembly needs 2 blocks or more");
    if (p.contacts.empty()) return fail(ErrorCode::kInvalidArgument, "no matching face pair given");
    if (auto ok = check_links(p, p.contacts, c, "pair"); !ok) return ok;
    if (auto ok = check_links(p, p.coplanar, c, "co-planar pair"); !ok) return ok;
    for (const LineLink& l : p.colinear)
        for (const LineRef& r : {l.a, l.b}) {
            Eigen::Vector3d x, d;
            double len = 0.0;
            if (r.block < 0 || std::size_t(r.block) >= p.blocks.size() ||
                !edge_line(p, r, Pose::Identity(), x, d, len))
                return fail(ErrorCode::kInvalidArgument,
                            "co-linear pair " + link_name(p, l) + ": no edge between those faces");
        }
    return check_connected(p);
}

Expected<AssemblyResult> assemble_blocks(const AssemblyProblem& p, const std::vector<Pose>& initial,
                                         const AssemblyConfig& c) {
    if (auto ok = validate_problem(p, c); !ok) return Unexpected(ok.error());
    const Prepared prep = prepare(p, c);
    AssemblyResult out{.T_world_block = initial};
    out.status = AssemblyStatus::kNotConverged;
    std::vector<Pose> before_last = out.T_world_block;  // Two steps back.
    std::vector<Pose> last = out.T_world_block;
    for (; out.iterations < c.max_iterations; ++out.iterations) {
        const bool constrained = c.non_penetration && out.iterations >= c.free_iterations;
        const double step = iterate(p, prep, c, constrained, out);
        if (out.status == AssemblyStatus::kInfeasible) return out;
        if (step < 0.0) return out;  // The QP's cap: kNotConverged with its message.
        out.last_step_m = step;
        // Settled also when two steps bring every block back where it was: the active set
        // alternating between two neighbouring poses (a 4 µm two-step cycle on the 3-block
        // wall with face planes, docs/reassembly.md).
        const bool cycling = largest_motion(p, before_last, out.T_world_block) < c.converged_step_m;
        before_last = std::move(last);
        last = out.T_world_block;
        if ((step < c.converged_step_m || cycling) && (constrained || !c.non_penetration)) {
            out.status = AssemblyStatus::kOk;
            ++out.iterations;
            break;
        }
    }
    if (out.status == AssemblyStatus::kOk && c.use_coplanar && c.use_colinear)
        flag_contradictions(p, c, out);
    if (out.status == AssemblyStatus::kNotConverged) {
        char step[64];
        std::snprintf(step, sizeof step, "%.4f", 1e3 * out.last_step_m);
        out.message = "no convergence in " + std::to_string(c.max_iterations) +
                      " iterations (last step " + step + " mm)";
    }
    return out;
}

}  // namespace anascan::reassembly
