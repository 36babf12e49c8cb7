// Face-pair scores (paper §5.2): checks on the faces, then the mirrored correspondence of
// their neighbours whose neighbourhood agrees best, and the holes on it.
#include "anascan/processing/reassembly/face_matching.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>

namespace anascan::reassembly {
namespace {

double linear_score(double difference, double tolerance) {
    return std::max(0.0, 1.0 - std::abs(difference) / std::max(tolerance, 1e-12));
}

double roughness_score(double ra, double rb, double tolerance) {
    if (!(ra > 0.0) || !(rb > 0.0)) return 0.0;
    return linear_score(std::log(ra / rb), tolerance);
}

// A neighbour of a face and the direction toward it: the angle of its normal about the
// face's normal, in the face's (width, height) axes.
struct NeighbourAngle {
    const FaceEdge* edge = nullptr;  ///< From the face to the neighbour.
    double angle = 0.0;
};

std::vector<NeighbourAngle> neighbour_angles(const BlockFeatures& block, int face) {
    const PlanarFace& f = block.faces[face];
    std::vector<NeighbourAngle> out;
    for (const FaceEdge& e : block.edges) {
        if (e.from != face) continue;
        const Eigen::Vector3d m = block.faces[e.to].normal;
        out.push_back({&e, std::atan2(m.dot(f.height_axis), m.dot(f.width_axis))});
    }
    return out;
}

constexpr double kPi = std::numbers::pi;
constexpr double kDegToRad = kPi / 180.0;

// |a - b| on the circle, for a - b within ±4π (angles from atan2 and their sums).
double angle_between(double a, double b) {
    double d = std::abs(a - b);
    while (d > 2.0 * kPi) d -= 2.0 * kPi;
    return d > kPi ? 2.0 * kPi - d : d;
}

// A hole seen from a joint face: its coordinate along a shared edge and its distance
// from the edge's line, with its size. The coordinate runs from the joint face's
// rectangle centre, not from the middle of the shared segment: chips and lost corners
// shorten the segment and move its middle, the dressed rectangle's sides stay.
struct JointHole {
    double along_m = 0.0, from_edge_m = 0.0;
    const FaceHole* hole = nullptr;
};

JointHole joint_hole(const PlanarFace& joint_face, const FaceEdge& e, const FaceHole& h) {
    const Eigen::Vector3d v = h.centre_m - e.point_m;
    const double from_edge = (v - v.dot(e.direction) * e.direction).norm();
    return {(h.centre_m - joint_face.centre_m).dot(e.direction), from_edge, &h};
}

// The extents of a hole are read from the floor points that survived erosion and chips
// (two halves of one clamp read 40-110 mm long, 10-15 mm wide on the 5 mm simulated
// lattice); its kind is what they keep. The position along the joint is read to a sample
// spacing and carries the evidence; the distance from the edge (the centre of what was
// read) and the width count a quarter and a half. Depth is left out: a half-clamp's
// pocket may or may not be reached.
double hole_size_error(const FaceHole& a, const FaceHole& b) {
    if (a.kind != b.kind) return 1e9;
    return 0.5 * std::abs(a.width_m - b.width_m);
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

// Corresponding neighbours of the two faces, by their edges from the faces.
using EdgePair = std::pair<const FaceEdge*, const FaceEdge*>;

struct Correspondence {
    std::vector<EdgePair> edges;
    double paired = 0.0;  ///< Share of the neighbours that found a partner.
    double neighbour_roughness = 0.0, edge_lengths = 0.0, holes = 0.0;
};

// A hole that runs out through the joint's edge (its near end within reach of the edge's
// line, the arris eroded): half of something cut across the joint, a clamp. A hole that
// stops short of the edge (a dowel of the bed joint above) is no feature of this joint.
bool opens_at_edge(const JointHole& j, const MatchConfig& config) {
    return j.from_edge_m - 0.5 * j.hole->length_m < config.hole_edge_reach_m;
}

// Holes of corresponding neighbours near the joint edge: symmetric about it means
// along_a + along_b = 0 (the edge directions are opposite once the blocks meet).
double neighbour_hole_score(const BlockFeatures& a, int fa, const BlockFeatures& b, int fb,
                            const Correspondence& c, const MatchConfig& config) {
    std::vector<JointHole> ha, hb;
    std::vector<int> pair_a, pair_b;
    for (std::size_t p = 0; p < c.edges.size(); ++p) {
        const FaceEdge &ea = *c.edges[p].first, &eb = *c.edges[p].second;
        for (const FaceHole& h : a.faces[ea.to].holes)
            if (JointHole j = joint_hole(a.faces[fa], ea, h); opens_at_edge(j, config))
                ha.push_back(j), pair_a.push_back(int(p));
        for (const FaceHole& h : b.faces[eb.to].holes)
            if (JointHole j = joint_hole(b.faces[fb], eb, h); opens_at_edge(j, config))
                hb.push_back(j), pair_b.push_back(int(p));
    }
    return hole_agreement(ha.size(), hb.size(), config.hole_tolerance_m,
                          [&](std::size_t i, std::size_t j) {
                              if (pair_a[i] != pair_b[j]) return 1e9;
                              return std::abs(ha[i].along_m + hb[j].along_m) +
                                     0.25 * std::abs(ha[i].from_edge_m - hb[j].from_edge_m) +
                                     hole_size_error(*ha[i].hole, *hb[j].hole);
                          });
}

// Dowels on the matching faces themselves (across a bed joint): the same distances to at
// least half of the corresponding edges (a staggered bed joint shares the façade and back
// edges, not the ends), the same size. Clamp channels in a face belong to the vertical
// joint at its edge, scored from that joint's faces; here they would only pair by chance.
double face_hole_score(const BlockFeatures& a, int fa, const BlockFeatures& b, int fb,
                       const Correspondence& c, const MatchConfig& config) {
    auto dowels = [](const PlanarFace& f) {
        std::vector<const FaceHole*> out;
        for (const FaceHole& h : f.holes)
            if (h.kind == HoleKind::kDowel) out.push_back(&h);
        return out;
    };
    const std::vector<const FaceHole*> holes_a = dowels(a.faces[fa]), holes_b = dowels(b.faces[fb]);
    return hole_agreement(
        holes_a.size(), holes_b.size(), config.hole_tolerance_m, [&](std::size_t i, std::size_t j) {
            std::vector<double> d;
            for (const auto& [ea, eb] : c.edges) {
                const JointHole ja = joint_hole(a.faces[fa], *ea, *holes_a[i]);
                const JointHole jb = joint_hole(b.faces[fb], *eb, *holes_b[j]);
                d.push_back(std::abs(ja.from_edge_m - jb.from_edge_m));
            }
            if (d.empty()) return 1e9;
            std::sort(d.begin(), d.end());
            return d[(d.size() - 1) / 2] + hole_size_error(*holes_a[i], *holes_b[j]);
        });
}

// The checks on the neighbourhoods; the holes are scored apart (score_holes), only on
// the placement that wins.
Correspondence score_neighbourhood(const BlockFeatures& a, const BlockFeatures& b,
                                   std::vector<EdgePair> edges, double neighbour_count,
                                   const MatchConfig& config) {
    Correspondence c{.edges = std::move(edges)};
    for (const auto& [ea, eb] : c.edges) {
        c.neighbour_roughness +=
            roughness_score(a.faces[ea->to].roughness_per_m2, b.faces[eb->to].roughness_per_m2,
                            config.roughness_tolerance);
        c.edge_lengths += linear_score(ea->length_m - eb->length_m, config.edge_length_tolerance_m);
    }
    // Over all neighbours of the face with more: a neighbour left unpaired scores nothing.
    const double n = std::max(1.0, neighbour_count);
    c.paired = double(c.edges.size()) / n;
    c.neighbour_roughness /= n;
    c.edge_lengths /= n;
    return c;
}

void score_holes(const BlockFeatures& a, int fa, const BlockFeatures& b, int fb, Correspondence& c,
                 const MatchConfig& config) {
    c.holes = std::max(neighbour_hole_score(a, fa, b, fb, c, config),
                       face_hole_score(a, fa, b, fb, c, config));
}

// The face's side that runs along a direction in its plane.
double extent_along(const PlanarFace& f, const Eigen::Vector3d& direction) {
    return std::abs(direction.dot(f.width_axis)) >= std::abs(direction.dot(f.height_axis))
               ? f.width_m
               : f.height_m;
}

// Width and height compared along corresponding edges: which side is the longer may differ
// between the two faces (a short end block's bed face), the sides that meet do not.
// Without corresponding neighbours, longer side against longer side.
double size_score(const PlanarFace& f, const PlanarFace& g, const std::vector<EdgePair>& edges,
                  const MatchConfig& config) {
    if (edges.empty())
        return 0.5 * (linear_score(f.width_m - g.width_m, config.size_tolerance_m) +
                      linear_score(f.height_m - g.height_m, config.size_tolerance_m));
    double sum = 0.0;
    for (const auto& [ea, eb] : edges)
        sum += linear_score(extent_along(f, ea->direction) - extent_along(g, eb->direction),
                            config.size_tolerance_m);
    return sum / double(edges.size());
}

double weighted(const MatchConfig& config, Check check, double score) {
    const int i = static_cast<int>(check);
    return config.enabled[i] ? config.weights[i] * score : 0.0;
}

// How well the two neighbourhoods agree (finishes, edges): this decides which sides meet.
double neighbourhood_value(const Correspondence& c, const MatchConfig& config) {
    return weighted(config, Check::kNeighbourCount, c.paired) +
           weighted(config, Check::kNeighbourRoughness, c.neighbour_roughness) +
           weighted(config, Check::kEdgeLengths, c.edge_lengths);
}

// The neighbour pairs of one placement of b's face against a's: when the faces meet face
// to face, b's directions are mirrored and turned by `turn` (a neighbour of b at angle β
// lies at turn - β about a's normal). Each neighbour of b pairs with the unpaired
// neighbour of a nearest that direction, when within the tolerance: an extra face (a
// broken corner, a carved band) on one block leaves the others' pairs in place.
std::vector<EdgePair> pairs_at_turn(const std::vector<NeighbourAngle>& na,
                                    const std::vector<NeighbourAngle>& nb, double turn,
                                    double tolerance) {
    std::vector<EdgePair> pairs;
    std::vector<bool> used(na.size(), false);
    for (const NeighbourAngle& g : nb) {
        std::size_t best = na.size();
        double best_gap = tolerance;
        for (std::size_t k = 0; k < na.size(); ++k)
            if (const double gap = angle_between(na[k].angle, turn - g.angle);
                !used[k] && gap < best_gap)
                best_gap = gap, best = k;
        if (best < na.size()) used[best] = true, pairs.emplace_back(na[best].edge, g.edge);
    }
    return pairs;
}

// Every placement that lays a neighbour of b's face onto a neighbour of a's (mirrored);
// the one whose neighbourhoods agree best (finishes, edges: a façade does not meet a
// back) decides which sides meet, and the holes are scored on it. Taking the best holes
// over every placement let clamps pair by chance across a façade meeting a back (top-1
// 70.1 % against 75.4 %, docs/reassembly.md). Placements that pair the same neighbours
// are scored once; an equal neighbourhood is decided by the holes.
Correspondence best_correspondence(const BlockFeatures& a, int fa, const BlockFeatures& b, int fb,
                                   const MatchConfig& config) {
    const std::vector<NeighbourAngle> na = neighbour_angles(a, fa), nb = neighbour_angles(b, fb);
    const double tolerance = config.neighbour_angle_tolerance_deg * kDegToRad;
    const double count = double(std::max(na.size(), nb.size()));
    std::vector<Correspondence> best;  // Every placement of the best neighbourhood value.
    double best_value = -1.0;
    std::vector<std::vector<EdgePair>> tried;
    std::vector<double> turns;  // Turns within a degree of one tried pair the same way.
    for (const NeighbourAngle& ga : na)
        for (const NeighbourAngle& gb : nb) {
            const double turn = ga.angle + gb.angle;
            if (std::any_of(turns.begin(), turns.end(),
                            [&](double t) { return angle_between(t, turn) < kDegToRad; }))
                continue;
            turns.push_back(turn);
            auto edges = pairs_at_turn(na, nb, turn, tolerance);
            std::sort(edges.begin(), edges.end());
            if (std::find(tried.begin(), tried.end(), edges) != tried.end()) continue;
            tried.push_back(edges);
            Correspondence c = score_neighbourhood(a, b, std::move(edges), count, config);
            const double value = neighbourhood_value(c, config);
            if (value > best_value) best_value = value, best.clear();
            if (value == best_value) best.push_back(std::move(c));
        }
    if (best.empty()) {
        Correspondence none;
        score_holes(a, fa, b, fb, none, config);
        return none;
    }
    for (Correspondence& c : best) score_holes(a, fa, b, fb, c, config);
    return *std::max_element(
        best.begin(), best.end(),
        [](const Correspondence& x, const Correspondence& y) { return x.holes < y.holes; });
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
    set(Check::kArea, linear_score((f.area_m2 - g.area_m2) / std::max(f.area_m2, g.area_m2),
                                   config.area_tolerance));
    set(Check::kRoughness,
        roughness_score(f.roughness_per_m2, g.roughness_per_m2, config.roughness_tolerance));
    Correspondence c = best_correspondence(a, fa, b, fb, config);
    set(Check::kSize, size_score(f, g, c.edges, config));
    // The paper's "same number of neighbours", read as how many neighbours correspond: a
    // façade reduced to a sliver by a moulding, or a broken corner's extra face, leaves
    // the other pairs standing.
    set(Check::kNeighbourCount, c.paired);
    set(Check::kNeighbourRoughness, c.neighbour_roughness);
    set(Check::kEdgeLengths, c.edge_lengths);
    set(Check::kHoles, c.holes);
    for (const auto& [ea, eb] : c.edges) s.neighbour_pairs.emplace_back(ea->to, eb->to);
    for (int i = 0; i < kCheckCount; ++i) s.score += weighted(config, Check(i), s.checks[i]);
    return s;
}

}  // namespace anascan::reassembly
