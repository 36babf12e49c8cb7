// Samples and linear rows of the block assembly: contacts (registration and
// non-penetration), co-planar faces and co-linear lines, each row nᵀ v_jk(x) = rhs.
#include <algorithm>
#include <cmath>

#include "assembly_steps.hpp"

namespace anascan::reassembly::assembly_detail {
namespace {

constexpr double kEdgeBand_m = 0.004;  // The RANSAC tolerance of the faces.

// A face's inliers and the unassigned points on its plane within its rectangle: the
// vertices along its edges, whose normals lean toward the next face, touch too.
bool on_face(const AssemblyBlock& block, int face, std::size_t i) {
    const int owner = block.features.point_face[i];
    if (owner == face) return true;
    if (owner >= 0) return false;
    const PlanarFace& f = block.features.faces[std::size_t(face)];
    const Eigen::Vector3d d = block.points.positions[i].cast<double>() - f.centre_m;
    return std::abs(d.dot(f.normal)) <= kEdgeBand_m &&
           std::abs(d.dot(f.width_axis)) <= 0.5 * f.width_m + kEdgeBand_m &&
           std::abs(d.dot(f.height_axis)) <= 0.5 * f.height_m + kEdgeBand_m;
}

FacePoints face_points(const AssemblyBlock& block, int face, int max_samples) {
    FacePoints out;
    const std::size_t count_all = std::min(block.features.point_face.size(), block.points.size());
    for (std::size_t i = 0; i < count_all; ++i) {
        if (!on_face(block, face, i)) continue;
        out.points.push_back(block.points.positions[i]);
        out.normals.push_back(block.points.has_normals() ? block.points.normals[i]
                                                         : Eigen::Vector3f::Zero());
    }
    const std::size_t n = out.points.size();
    const std::size_t count = std::min<std::size_t>(n, std::size_t(std::max(1, max_samples)));
    for (std::size_t s = 0; s < count; ++s) out.samples.push_back(int(s * n / count));
    out.tree = std::make_unique<KdTree>(out.points);
    return out;
}

// Rows of the samples of face `from` against the closest points y of face `to`, along the
// outward vertex normal at y (JointNormal::kVertex) or the normal of `to`'s fitted plane
// (kFacePlane). Vertex normals carry the joint's own geometry (drafted margins, tool
// marks), and lean at edges: on the simulated wall their rows pull a block 1 mm off the
// truth and lock starts 5 degrees off in contradictory poses; plane normals do neither but
// know nothing of the margins (docs/reassembly.md, the figures of both).
void contact_rows(const AssemblyProblem& pr, const Prepared& p, const FaceRef& from,
                  const FaceRef& to, const std::vector<Pose>& T, const AssemblyConfig& config,
                  int link, std::vector<Row>& out) {
    const Eigen::Vector3d plane_normal =
        pr.blocks[std::size_t(to.block)].features.faces[std::size_t(to.face)].normal;
    const FacePoints& src = p.faces[std::size_t(from.block)][std::size_t(from.face)];
    const FacePoints& dst = p.faces[std::size_t(to.block)][std::size_t(to.face)];
    const Pose& Tj = T[std::size_t(from.block)];
    const Pose& Tk = T[std::size_t(to.block)];
    const Pose T_k_j = Tk.inverse() * Tj;
    for (int s : src.samples) {
        const Eigen::Vector3f q = (T_k_j * src.points[std::size_t(s)].cast<double>()).cast<float>();
        Neighbor nb;
        if (!dst.tree->nearest(q, nb)) continue;
        const Eigen::Vector3d y = dst.points[nb.index].cast<double>();
        const Eigen::Vector3d n = config.joint_normal == JointNormal::kFacePlane
                                      ? plane_normal
                                      : dst.normals[nb.index].cast<double>().normalized();
        const Eigen::Vector3d d = q.cast<double>() - y;
        if ((d - d.dot(n) * n).norm() > config.contact_gate_m) continue;  // Beyond the face.
        out.push_back({.j = from.block,
                       .k = to.block,
                       .x = Tj * src.points[std::size_t(s)].cast<double>(),
                       .n = Tk.linear() * n,
                       .rhs = -d.dot(n),
                       .link = link});
    }
}

void plane_rows(const AssemblyProblem& pr, const FaceRef& from, const FaceRef& to,
                const std::vector<Pose>& T, const AssemblyConfig& config, int link,
                std::vector<Row>& out) {
    const PlanarFace& a = pr.blocks[std::size_t(from.block)].features.faces[std::size_t(from.face)];
    const PlanarFace& b = pr.blocks[std::size_t(to.block)].features.faces[std::size_t(to.face)];
    const Pose& Tj = T[std::size_t(from.block)];
    const Pose& Tk = T[std::size_t(to.block)];
    const Eigen::Vector3d n = Tk.linear() * b.normal, c = Tk * b.centre_m;
    for (const Eigen::Vector3d& s : rectangle_samples(a, config.plane_samples_per_side)) {
        const Eigen::Vector3d x = Tj * s;
        out.push_back(
            {.j = from.block, .k = to.block, .x = x, .n = n, .rhs = -n.dot(x - c), .link = link});
    }
}

void line_rows(const AssemblyProblem& pr, const LineRef& from, const LineRef& to,
               const std::vector<Pose>& T, const AssemblyConfig& config, int link,
               std::vector<Row>& out) {
    Eigen::Vector3d pa, da, pb, db;
    double la = 0.0, lb = 0.0;
    if (!edge_line(pr, from, T[std::size_t(from.block)], pa, da, la) ||
        !edge_line(pr, to, T[std::size_t(to.block)], pb, db, lb))
        return;
    const Eigen::Vector3d e1 = db.unitOrthogonal(), e2 = db.cross(e1);
    const int count = std::max(2, config.line_samples);
    for (int s = 0; s < count; ++s) {
        const Eigen::Vector3d x = pa + (double(s) / (count - 1) - 0.5) * la * da;
        for (const Eigen::Vector3d& e : {e1, e2})
            out.push_back({.j = from.block,
                           .k = to.block,
                           .x = x,
                           .n = e,
                           .rhs = -e.dot(x - pb),
                           .link = link});
    }
}

}  // namespace

std::vector<Eigen::Vector3d> rectangle_samples(const PlanarFace& f, int per_side) {
    std::vector<Eigen::Vector3d> out;
    const int n = std::max(2, per_side);
    for (int u = 0; u < n; ++u)
        for (int v = 0; v < n; ++v)
            out.push_back(f.centre_m +
                          (double(u) / (n - 1) - 0.5) * 0.9 * f.width_m * f.width_axis +
                          (double(v) / (n - 1) - 0.5) * 0.9 * f.height_m * f.height_axis);
    return out;
}

bool edge_line(const AssemblyProblem& pr, const LineRef& ref, const Pose& T,
               Eigen::Vector3d& point_m, Eigen::Vector3d& direction, double& length_m) {
    for (const FaceEdge& e : pr.blocks[std::size_t(ref.block)].features.edges) {
        if (!((e.from == ref.face_a && e.to == ref.face_b) ||
              (e.from == ref.face_b && e.to == ref.face_a)))
            continue;
        point_m = T * e.point_m, direction = T.linear() * e.direction, length_m = e.length_m;
        return true;
    }
    return false;
}

Prepared prepare(const AssemblyProblem& pr, const AssemblyConfig& config) {
    Prepared p;
    p.faces.resize(pr.blocks.size());
    for (std::size_t b = 0; b < pr.blocks.size(); ++b)
        p.faces[b].resize(pr.blocks[b].features.faces.size());
    for (const FaceLink& l : pr.contacts)
        for (const FaceRef& r : {l.a, l.b})
            if (!p.faces[std::size_t(r.block)][std::size_t(r.face)].tree)
                p.faces[std::size_t(r.block)][std::size_t(r.face)] = face_points(
                    pr.blocks[std::size_t(r.block)], r.face, config.contact_samples_per_face);
    p.slot.assign(pr.blocks.size(), 0);
    for (int f : pr.fixed.empty() ? std::vector<int>{0} : pr.fixed) p.slot[std::size_t(f)] = -1;
    for (int& s : p.slot) s = s < 0 ? -1 : p.num_slots++;
    return p;
}

Rows build_rows(const AssemblyProblem& pr, const Prepared& p, const std::vector<Pose>& T,
                const AssemblyConfig& config) {
    Rows rows;
    for (std::size_t l = 0; l < pr.contacts.size(); ++l) {
        contact_rows(pr, p, pr.contacts[l].a, pr.contacts[l].b, T, config, int(l), rows.contact);
        contact_rows(pr, p, pr.contacts[l].b, pr.contacts[l].a, T, config, int(l), rows.contact);
    }
    for (std::size_t l = 0; config.use_coplanar && l < pr.coplanar.size(); ++l) {
        plane_rows(pr, pr.coplanar[l].a, pr.coplanar[l].b, T, config, int(l), rows.coplanar);
        plane_rows(pr, pr.coplanar[l].b, pr.coplanar[l].a, T, config, int(l), rows.coplanar);
    }
    for (std::size_t l = 0; config.use_colinear && l < pr.colinear.size(); ++l) {
        line_rows(pr, pr.colinear[l].a, pr.colinear[l].b, T, config, int(l), rows.colinear);
        line_rows(pr, pr.colinear[l].b, pr.colinear[l].a, T, config, int(l), rows.colinear);
    }
    return rows;
}

Eigen::MatrixXd row_matrix(const std::vector<Row>& rows, const Prepared& p, const Frames& f,
                           double weight) {
    Eigen::MatrixXd M = Eigen::MatrixXd::Zero(Eigen::Index(rows.size()), 6 * p.num_slots);
    for (std::size_t i = 0; i < rows.size(); ++i) {
        const Row& r = rows[i];
        // nᵀ(c × (x - p) + c̄') = c·((x - p) × n) + c̄'·n, with c scaled by the length.
        for (const auto& [block, sign] : {std::pair{r.j, 1.0}, std::pair{r.k, -1.0}}) {
            const int s = p.slot[std::size_t(block)];
            if (s < 0) continue;
            const Eigen::Vector3d arm = (r.x - f.reference_m[std::size_t(block)]).cross(r.n);
            M.block<1, 3>(Eigen::Index(i), 6 * s) =
                sign * weight * arm.transpose() / f.length_m[std::size_t(block)];
            M.block<1, 3>(Eigen::Index(i), 6 * s + 3) = sign * weight * r.n.transpose();
        }
    }
    return M;
}

}  // namespace anascan::reassembly::assembly_detail
