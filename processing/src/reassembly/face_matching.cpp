// Face-pair scores (paper §5.2): checks on the faces, then the best mirrored cyclic
// correspondence of their neighbours.
#include "anascan/processing/reassembly/face_matching.hpp"

#include <algorithm>
#include <cassert>
#include <cmath>

namespace anascan::reassembly {
namespace {

double linear_score(double difference, double tolerance) {
    return std::max(0.0, 1.0 - std::abs(difference) / std::max(tolerance, 1e-12));
}

double roughness_score(double ra, double rb, double tolerance) {
    if (!(ra > 0.0) || !(rb > 0.0)) return 0.0;
    return linear_score(std::log(ra / rb), tolerance);
}

// Neighbours of a face in counter-clockwise order about its normal.
std::vector<int> ordered_neighbours(const BlockFeatures& block, int face) {
    const PlanarFace& f = block.faces[face];
    std::vector<std::pair<double, int>> by_angle;
    for (int n : block.neighbours(face)) {
        const Eigen::Vector3d m = block.faces[n].normal;
        by_angle.emplace_back(std::atan2(m.dot(f.height_axis), m.dot(f.width_axis)), n);
    }
    std::sort(by_angle.begin(), by_angle.end());
    std::vector<int> out;
    for (const auto& [angle, n] : by_angle) out.push_back(n);
    return out;
}

// The edge from -> to; `to` is a neighbour of `from`, so the edge exists.
const FaceEdge& find_edge(const BlockFeatures& block, int from, int to) {
    for (const FaceEdge& e : block.edges)
        if (e.from == from && e.to == to) return e;
    assert(false && "find_edge: not neighbours");
    return block.edges.front();
}

// A hole seen from a joint face: its coordinate along a shared edge (from the edge's
// middle, along the edge's direction) and distance from it, with its size.
struct JointHole {
    double along_m = 0.0, from_edge_m = 0.0;
    const FaceHole* hole = nullptr;
};

JointHole joint_hole(const FaceEdge& e, const FaceHole& h) {
    const Eigen::Vector3d v = h.centre_m - e.point_m;
    const double along = v.dot(e.direction);
    return {along, (v - along * e.direction).norm(), &h};
}

double hole_size_error(const FaceHole& a, const FaceHole& b) {
    if (a.kind != b.kind) return 1e9;
    return std::abs(a.length_m - b.length_m) + std::abs(a.width_m - b.width_m) +
           0.5 * std::abs(a.depth_m - b.depth_m);
}

// Greedy best agreement of two hole lists; err(i, j) < tolerance counts.
template <class Error>
double hole_agreement(std::size_t na, std::size_t nb, double tolerance, Error err) {
    if (na + nb == 0) return 0.0;
    std::vector<bool> used(nb, false);
    double sum = 0.0;
    for (std::size_t i = 0; i < na; ++i) {
        double best = 0.0;
        std::size_t best_j = nb;
        for (std::size_t j = 0; j < nb; ++j) {
            const double s = used[j] ? 0.0 : linear_score(err(i, j), tolerance);
            if (s > best) best = s, best_j = j;
        }
        if (best_j < nb) used[best_j] = true, sum += best;
    }
    return 2.0 * sum / double(na + nb);
}

struct Correspondence {
    std::vector<std::pair<int, int>> pairs;
    double neighbour_roughness = 0.0, edge_lengths = 0.0, holes = 0.0;
};

// Holes of corresponding neighbours near the joint edge: symmetric about it means
// along_a + along_b = 0 (the edge directions are opposite once the blocks meet).
double neighbour_hole_score(const BlockFeatures& a, int fa, const BlockFeatures& b, int fb,
                            const Correspondence& c, const MatchConfig& config) {
    std::vector<JointHole> ha, hb;
    std::vector<int> pair_a, pair_b;
    for (std::size_t p = 0; p < c.pairs.size(); ++p) {
        const FaceEdge& ea = find_edge(a, fa, c.pairs[p].first);
        const FaceEdge& eb = find_edge(b, fb, c.pairs[p].second);
        for (const FaceHole& h : a.faces[c.pairs[p].first].holes)
            if (JointHole j = joint_hole(ea, h); j.from_edge_m < config.hole_edge_distance_m)
                ha.push_back(j), pair_a.push_back(int(p));
        for (const FaceHole& h : b.faces[c.pairs[p].second].holes)
            if (JointHole j = joint_hole(eb, h); j.from_edge_m < config.hole_edge_distance_m)
                hb.push_back(j), pair_b.push_back(int(p));
    }
    return hole_agreement(ha.size(), hb.size(), config.hole_tolerance_m,
                          [&](std::size_t i, std::size_t j) {
                              if (pair_a[i] != pair_b[j]) return 1e9;
                              return std::abs(ha[i].along_m + hb[j].along_m) +
                                     std::abs(ha[i].from_edge_m - hb[j].from_edge_m) +
                                     hole_size_error(*ha[i].hole, *hb[j].hole);
                          });
}

// Holes on the matching faces themselves (dowels across a bed joint): the same distances
// to at least half of the corresponding edges, the same kind and size.
double face_hole_score(const BlockFeatures& a, int fa, const BlockFeatures& b, int fb,
                       const Correspondence& c, const MatchConfig& config) {
    const auto& holes_a = a.faces[fa].holes;
    const auto& holes_b = b.faces[fb].holes;
    return hole_agreement(
        holes_a.size(), holes_b.size(), config.hole_tolerance_m, [&](std::size_t i, std::size_t j) {
            std::vector<double> d;
            for (const auto& [na, nb] : c.pairs) {
                const JointHole ja = joint_hole(find_edge(a, fa, na), holes_a[i]);
                const JointHole jb = joint_hole(find_edge(b, fb, nb), holes_b[j]);
                d.push_back(std::abs(ja.from_edge_m - jb.from_edge_m));
            }
            if (d.empty()) return 1e9;
            std::sort(d.begin(), d.end());
            return d[(d.size() - 1) / 2] + hole_size_error(holes_a[i], holes_b[j]);
        });
}

Correspondence score_correspondence(const BlockFeatures& a, int fa, const BlockFeatures& b, int fb,
                                    std::vector<std::pair<int, int>> pairs,
                                    const MatchConfig& config) {
    Correspondence c{.pairs = std::move(pairs)};
    for (const auto& [na, nb] : c.pairs) {
        c.neighbour_roughness += roughness_score(
            a.faces[na].roughness_per_m2, b.faces[nb].roughness_per_m2, config.roughness_tolerance);
        c.edge_lengths +=
            linear_score(find_edge(a, fa, na).length_m - find_edge(b, fb, nb).length_m,
                         config.edge_length_tolerance_m);
    }
    const double n = std::max<double>(1.0, double(c.pairs.size()));
    c.neighbour_roughness /= n;
    c.edge_lengths /= n;
    const double near_edge = neighbour_hole_score(a, fa, b, fb, c, config);
    const double on_face = face_hole_score(a, fa, b, fb, c, config);
    c.holes = std::max(near_edge, on_face);
    return c;
}

double weighted(const MatchConfig& config, Check check, double score) {
    const int i = static_cast<int>(check);
    return config.enabled[i] ? config.weights[i] * score : 0.0;
}

double correspondence_value(const Correspondence& c, const MatchConfig& config) {
    return weighted(config, Check::kNeighbourRoughness, c.neighbour_roughness) +
           weighted(config, Check::kEdgeLengths, c.edge_lengths) +
           weighted(config, Check::kHoles, c.holes);
}

// Every mirrored cyclic correspondence of the neighbours; the best by weighted score.
Correspondence best_correspondence(const BlockFeatures& a, int fa, const BlockFeatures& b, int fb,
                                   const MatchConfig& config) {
    const std::vector<int> na = ordered_neighbours(a, fa), nb = ordered_neighbours(b, fb);
    Correspondence best;
    double best_value = -1.0;
    const std::size_t m = std::min(na.size(), nb.size());
    for (std::size_t r = 0; r < nb.size(); ++r) {
        std::vector<std::pair<int, int>> pairs;
        for (std::size_t k = 0; k < m; ++k)
            pairs.emplace_back(na[k], nb[(r + nb.size() - k % nb.size()) % nb.size()]);
        Correspondence c = score_correspondence(a, fa, b, fb, std::move(pairs), config);
        if (const double v = correspondence_value(c, config); v > best_value)
            best_value = v, best = std::move(c);
    }
    return best;
}

}  // namespace

const char* to_string(Check check) {
    static constexpr const char* kNames[kCheckCount] = {
        "neighbours", "area", "size", "roughness", "nb-roughness", "edges", "holes"};
    return kNames[static_cast<int>(check)];
}

FacePairScore score_face_pair(const BlockFeatures& a, int fa, const BlockFeatures& b, int fb,
                              const MatchConfig& config) {
    const PlanarFace &f = a.faces[fa], &g = b.faces[fb];
    FacePairScore s{.a = {0, fa}, .b = {0, fb}};
    auto set = [&](Check c, double v) { s.checks[static_cast<int>(c)] = v; };
    set(Check::kNeighbourCount, a.neighbours(fa).size() == b.neighbours(fb).size() ? 1.0 : 0.0);
    set(Check::kArea, linear_score((f.area_m2 - g.area_m2) / std::max(f.area_m2, g.area_m2),
                                   config.area_tolerance));
    set(Check::kSize, 0.5 * (linear_score(f.width_m - g.width_m, config.size_tolerance_m) +
                             linear_score(f.height_m - g.height_m, config.size_tolerance_m)));
    set(Check::kRoughness,
        roughness_score(f.roughness_per_m2, g.roughness_per_m2, config.roughness_tolerance));
    Correspondence c = best_correspondence(a, fa, b, fb, config);
    set(Check::kNeighbourRoughness, c.neighbour_roughness);
    set(Check::kEdgeLengths, c.edge_lengths);
    set(Check::kHoles, c.holes);
    s.neighbour_pairs = std::move(c.pairs);
    for (int i = 0; i < kCheckCount; ++i) s.score += weighted(config, Check(i), s.checks[i]);
    return s;
}

}  // namespace anascan::reassembly
