// Verification of an assembly on the dense models (see the header).
#include "anascan/processing/reassembly/assembly_check.hpp"

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <limits>
#include <optional>

#include "anascan/processing/spatial/kdtree.hpp"
#include "assembly_steps.hpp"
#include "mesh_distance.hpp"

namespace anascan::reassembly {
namespace {

using assembly_detail::edge_line;

double angle_deg(const Eigen::Vector3d& a, const Eigen::Vector3d& b) {
    return std::atan2(a.cross(b).norm(), a.dot(b)) * 180.0 / M_PI;
}

double quantile(std::vector<double> v, double q) {
    if (v.empty()) return 0.0;
    const auto k = std::size_t(q * double(v.size() - 1));
    std::nth_element(v.begin(), v.begin() + std::ptrdiff_t(k), v.end());
    return v[k];
}

// Signed distances of the points of face `from` to block `to` in front of it, also kept
// per point in `point_gap`.
void face_gaps(const AssemblyProblem& p, const FaceRef& from, int to, const KdTree& tree,
               const std::vector<Pose>& T, const CheckConfig& c, std::vector<double>& out,
               std::vector<float>& point_gap) {
    const AssemblyBlock& a = p.blocks[std::size_t(from.block)];
    const AssemblyBlock& b = p.blocks[std::size_t(to)];
    const Pose T_b_a = T[std::size_t(to)].inverse() * T[std::size_t(from.block)];
    for (std::size_t i = 0; i < a.features.point_face.size(); ++i) {
        if (a.features.point_face[i] != from.face) continue;
        const Eigen::Vector3d x = T_b_a * a.points.positions[i].cast<double>();
        Neighbor nb;
        if (!tree.nearest(x.cast<float>(), nb)) continue;
        const Eigen::Vector3d d = x - b.points.positions[nb.index].cast<double>();
        const Eigen::Vector3d n = b.points.normals[nb.index].cast<double>().normalized();
        if ((d - d.dot(n) * n).norm() > c.gate_m) continue;
        out.push_back(d.dot(n));
        point_gap[i] = float(d.dot(n));
    }
}

struct Box {
    Eigen::Vector3d lo = Eigen::Vector3d::Constant(1e300), hi = Eigen::Vector3d::Constant(-1e300);
};

// The signed distance of x to block b from its vertex normals (a block without triangles):
// inside when both the nearest vertex and the median over the nearest vertices say so,
// at most as deep as the nearest vertex is far. Nothing when no vertex is within near_m.
std::optional<double> vertex_signed_distance(const PointCloud& pb, const KdTree& tree,
                                             const Eigen::Vector3d& x, const CheckConfig& c) {
    std::vector<Neighbor> nbs;
    tree.knn(x.cast<float>(), std::size_t(c.sign_neighbours), nbs);
    if (nbs.empty() || nbs[0].distance_sq_m2 > c.near_m * c.near_m) return std::nullopt;
    std::vector<double> sds;
    for (const Neighbor& nb : nbs)
        sds.push_back(pb.normals[nb.index].cast<double>().normalized().dot(
            x - pb.positions[nb.index].cast<double>()));
    return std::max({quantile(sds, 0.5), sds[0], -std::sqrt(double(nbs[0].distance_sq_m2))});
}

// The signed distance of x to a block's mesh by pseudo-normals; a closest feature on a
// hole's rim counts as outside (an open mesh has no inside there).
std::optional<double> mesh_signed_distance(const detail::MeshDistance& mesh,
                                           const Eigen::Vector3d& x, const CheckConfig& c) {
    detail::SignedDistance sd;
    if (!mesh.signed_distance(x, sd) || std::abs(sd.distance_m) > c.near_m) return std::nullopt;
    return sd.boundary ? std::abs(sd.distance_m) : sd.distance_m;
}

// What the check knows of one block: its points' tree, bounds and mesh distance.
struct Target {
    KdTree tree;
    Box box;
    std::optional<detail::MeshDistance> mesh;
    double longest_edge_m = 0.0;  ///< The mesh is within this of its nearest vertex.
};

// Cheap rejection by the nearest vertex: no surface of the block within near_m of x.
bool far_from(const Target& t, const Eigen::Vector3d& x, const CheckConfig& c) {
    Neighbor nb;
    if (!t.tree.nearest(x.cast<float>(), nb)) return true;
    return std::sqrt(double(nb.distance_sq_m2)) > c.near_m + t.longest_edge_m;
}

double longest_edge(const AssemblyBlock& b) {
    double out = 0.0;
    for (const Eigen::Vector3i& f : b.triangles)
        for (int k = 0; k < 3; ++k)
            out = std::max(out, double((b.points.positions[std::size_t(f[k])] -
                                        b.points.positions[std::size_t(f[(k + 1) % 3])])
                                           .norm()));
    return out;
}

// Penetration of block a's points into block b (signed distance below -tolerance).
void penetration(const AssemblyProblem& p, int a, int b, const Target& target,
                 const std::vector<Pose>& T, const CheckConfig& c, AssemblyCheck& out,
                 double& depth_sum) {
    const Pose T_b_a = T[std::size_t(b)].inverse() * T[std::size_t(a)];
    const PointCloud& pa = p.blocks[std::size_t(a)].points;
    std::vector<float>& depth = out.depth_m[std::size_t(a)];
    for (std::size_t i = 0; i < pa.positions.size(); ++i) {
        const Eigen::Vector3d x = T_b_a * pa.positions[i].cast<double>();
        if ((x.array() < target.box.lo.array() - c.near_m).any() ||
            (x.array() > target.box.hi.array() + c.near_m).any() ||
            (target.mesh && far_from(target, x, c)))
            continue;
        const std::optional<double> sd =
            target.mesh
                ? mesh_signed_distance(*target.mesh, x, c)
                : vertex_signed_distance(p.blocks[std::size_t(b)].points, target.tree, x, c);
        if (!sd) continue;
        ++out.measured_points;
        if (*sd >= -c.tolerance_m) continue;
        ++out.penetrating_points;
        depth[i] = std::max(depth[i], float(-*sd));
        depth_sum += -*sd;
        out.penetration_max_m = std::max(out.penetration_max_m, -*sd);
    }
}

}  // namespace

void check_links(const AssemblyProblem& p, const std::vector<Pose>& T, const CheckConfig& c,
                 AssemblyCheck& out) {
    auto face = [&](const FaceRef& r) -> const PlanarFace& {
        return p.blocks[std::size_t(r.block)].features.faces[std::size_t(r.face)];
    };
    for (const FaceLink& l : p.coplanar) {
        const PlanarFace &a = face(l.a), &b = face(l.b);
        const Pose &Ta = T[std::size_t(l.a.block)], &Tb = T[std::size_t(l.b.block)];
        const Eigen::Vector3d na = Ta.linear() * a.normal, nb = Tb.linear() * b.normal;
        const double offset = 0.5 * (std::abs(nb.dot(Ta * a.centre_m - Tb * b.centre_m)) +
                                     std::abs(na.dot(Tb * b.centre_m - Ta * a.centre_m)));
        out.coplanar.push_back({link_name(p, l), angle_deg(na, nb), offset});
    }
    for (const LineLink& l : p.colinear) {
        Eigen::Vector3d pa, da, pb, db;
        double la = 0.0, lb = 0.0;
        if (!edge_line(p, l.a, T[std::size_t(l.a.block)], pa, da, la) ||
            !edge_line(p, l.b, T[std::size_t(l.b.block)], pb, db, lb))
            continue;
        double far = 0.0;
        for (int s = 0; s < std::max(2, c.line_samples); ++s) {
            const Eigen::Vector3d x =
                pa + (double(s) / (std::max(2, c.line_samples) - 1) - 0.5) * la * da;
            far = std::max(far, (x - pb - (x - pb).dot(db) * db).norm());
        }
        out.colinear.push_back(
            {link_name(p, l), std::min(angle_deg(da, db), angle_deg(da, -db)), far});
    }
}

AssemblyCheck check_assembly(const AssemblyProblem& p, const std::vector<Pose>& T,
                             const CheckConfig& c) {
    AssemblyCheck out;
    std::vector<Target> targets;
    targets.reserve(p.blocks.size());
    for (const AssemblyBlock& block : p.blocks) {
        Target& t = targets.emplace_back(Target{.tree = KdTree(block.points.positions)});
        for (const auto& x : block.points.positions)
            t.box.lo = t.box.lo.cwiseMin(x.cast<double>()),
            t.box.hi = t.box.hi.cwiseMax(x.cast<double>());
        if (!block.triangles.empty()) t.mesh.emplace(block.points.positions, block.triangles);
        t.longest_edge_m = longest_edge(block);
    }
    double depth_sum = 0.0;
    for (const AssemblyBlock& b : p.blocks) {
        out.depth_m.emplace_back(b.points.size(), 0.0f);
        out.gap_m.emplace_back(b.points.size(), std::numeric_limits<float>::quiet_NaN());
    }
    for (std::size_t a = 0; a < p.blocks.size(); ++a)
        for (std::size_t b = 0; b < p.blocks.size(); ++b)
            if (a != b) penetration(p, int(a), int(b), targets[b], T, c, out, depth_sum);
    out.penetration_mean_m =
        out.penetrating_points ? depth_sum / double(out.penetrating_points) : 0.0;
    for (const FaceLink& l : p.contacts) {
        std::vector<double> gaps;
        face_gaps(p, l.a, l.b.block, targets[std::size_t(l.b.block)].tree, T, c, gaps,
                  out.gap_m[std::size_t(l.a.block)]);
        face_gaps(p, l.b, l.a.block, targets[std::size_t(l.a.block)].tree, T, c, gaps,
                  out.gap_m[std::size_t(l.b.block)]);
        ContactCheck cc{.pair = link_name(p, l), .points = gaps.size()};
        if (!gaps.empty()) {
            cc.gap_median_m = quantile(gaps, 0.5), cc.gap_p95_m = quantile(gaps, 0.95);
            cc.gap_max_m = *std::ranges::max_element(gaps);
            cc.gap_min_m = *std::ranges::min_element(gaps);
        }
        out.contacts.push_back(cc);
    }
    check_links(p, T, c, out);
    return out;
}

}  // namespace anascan::reassembly
