// Initial placement of the blocks (paper §5.3): Horn's closed-form absolute orientation
// from six points per matched face, breadth-first from the fixed blocks.
#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <deque>

#include "anascan/processing/reassembly/block_assembly.hpp"

namespace anascan::reassembly {
namespace {

const PlanarFace& face_of(const AssemblyProblem& p, const FaceRef& r) {
    return p.blocks[std::size_t(r.block)].features.faces[std::size_t(r.face)];
}

// The neighbour pair (face of a's block, face of b's block) to align: the hint's faces
// when they neighbour the matched faces, else the mirrored neighbours of most similar ρ.
std::pair<int, int> aligned_neighbours(const AssemblyProblem& p, const FaceLink& link,
                                       const FaceLink* hint) {
    const BlockFeatures& fa = p.blocks[std::size_t(link.a.block)].features;
    const BlockFeatures& fb = p.blocks[std::size_t(link.b.block)].features;
    if (hint != nullptr) {
        const bool swapped = hint->a.block != link.a.block;
        const FaceRef ha = swapped ? hint->b : hint->a, hb = swapped ? hint->a : hint->b;
        const auto na = fa.neighbours(link.a.face), nb = fb.neighbours(link.b.face);
        if (std::ranges::count(na, ha.face) > 0 && std::ranges::count(nb, hb.face) > 0)
            return {ha.face, hb.face};
    }
    const FacePairScore s = score_face_pair(fa, link.a.face, fb, link.b.face, MatchConfig{});
    std::pair<int, int> best{-1, -1};
    double best_diff = 1e300;
    for (const auto& [i, k] : s.neighbour_pairs) {
        const double ri = std::max(1e-9, fa.faces[std::size_t(i)].roughness_per_m2);
        const double rk = std::max(1e-9, fb.faces[std::size_t(k)].roughness_per_m2);
        if (const double diff = std::abs(std::log(ri / rk)); diff < best_diff)
            best_diff = diff, best = {i, k};
    }
    return best;
}

Eigen::Vector3d in_plane_unit(const Eigen::Vector3d& v, const Eigen::Vector3d& n,
                              const Eigen::Vector3d& fallback) {
    const Eigen::Vector3d t = v - v.dot(n) * n;
    return t.norm() > 1e-6 ? t.normalized() : fallback;
}

std::vector<Eigen::Vector3d> six_points(const Eigen::Vector3d& c, const Eigen::Vector3d& n,
                                        const Eigen::Vector3d& m) {
    const Eigen::Vector3d k = n.cross(m);
    return {c + 0.5 * n, c - 0.5 * n, c + 0.5 * m, c - 0.5 * m, c + 0.5 * k, c - 0.5 * k};
}

}  // namespace

Pose absolute_orientation(const std::vector<Eigen::Vector3d>& from,
                          const std::vector<Eigen::Vector3d>& to) {
    Eigen::Matrix3Xd P(3, Eigen::Index(from.size())), Q(3, Eigen::Index(to.size()));
    for (std::size_t i = 0; i < from.size(); ++i)
        P.col(Eigen::Index(i)) = from[i], Q.col(Eigen::Index(i)) = to[i];
    Pose T = Pose::Identity();
    T.matrix() = Eigen::umeyama(P, Q, false);
    return T;
}

Pose place_on_face(const AssemblyProblem& p, const FaceLink& link, const Pose& T_world_b,
                   const FaceLink* hint) {
    const PlanarFace& a = face_of(p, link.a);
    const PlanarFace& b = face_of(p, link.b);
    const auto [ia, ib] = aligned_neighbours(p, link, hint);
    const BlockFeatures& fa = p.blocks[std::size_t(link.a.block)].features;
    const BlockFeatures& fb = p.blocks[std::size_t(link.b.block)].features;
    const Eigen::Vector3d ma =
        ia < 0 ? a.width_axis
               : in_plane_unit(fa.faces[std::size_t(ia)].normal, a.normal, a.width_axis);
    const Eigen::Vector3d nb = T_world_b.linear() * b.normal;
    const Eigen::Vector3d wb = T_world_b.linear() * b.width_axis;
    const Eigen::Vector3d mb =
        ib < 0 ? wb : in_plane_unit(T_world_b.linear() * fb.faces[std::size_t(ib)].normal, nb, wb);
    // Face to face: a's outward normal goes onto b's inward one.
    return absolute_orientation(six_points(a.centre_m, a.normal, ma),
                                six_points(T_world_b * b.centre_m, -nb, mb));
}

Expected<std::vector<Pose>> initial_placement(const AssemblyProblem& p,
                                              const AssemblyConfig& config) {
    if (auto ok = validate_problem(p, config); !ok) return Unexpected(ok.error());
    std::vector<Pose> T(p.blocks.size(), Pose::Identity());
    std::vector<char> placed(p.blocks.size(), 0);
    std::deque<int> queue;
    for (int f : p.fixed.empty() ? std::vector<int>{0} : p.fixed)
        placed[std::size_t(f)] = 1, queue.push_back(f);
    while (!queue.empty()) {
        const int k = queue.front();
        queue.pop_front();
        for (FaceLink link : p.contacts) {
            if (link.a.block == k) std::swap(link.a, link.b);
            if (link.b.block != k || placed[std::size_t(link.a.block)]) continue;
            const FaceLink* hint = nullptr;
            for (const FaceLink& c : p.coplanar)
                if ((c.a.block == link.a.block && c.b.block == k) ||
                    (c.b.block == link.a.block && c.a.block == k))
                    hint = &c;
            T[std::size_t(link.a.block)] = place_on_face(p, link, T[std::size_t(k)], hint);
            placed[std::size_t(link.a.block)] = 1;
            queue.push_back(link.a.block);
        }
    }
    return T;
}

std::string link_name(const AssemblyProblem& p, const FaceLink& l) {
    return p.blocks[std::size_t(l.a.block)].id + ":" + std::to_string(l.a.face) + "=" +
           p.blocks[std::size_t(l.b.block)].id + ":" + std::to_string(l.b.face);
}

std::string link_name(const AssemblyProblem& p, const LineLink& l) {
    auto one = [&](const LineRef& r) {
        return p.blocks[std::size_t(r.block)].id + ":" + std::to_string(r.face_a) + "/" +
               std::to_string(r.face_b);
    };
    return one(l.a) + "=" + one(l.b);
}

}  // namespace anascan::reassembly
