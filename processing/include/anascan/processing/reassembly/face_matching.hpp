#pragma once
/// \file
/// Face matching and neighbour proposals (method paper §5.2). Every pair of faces of
/// different blocks is scored: each consistency check adds its score (0..1, times its
/// weight) and no single failed check rejects a pair, because eroded features fail checks.
/// The checks on the faces themselves (area, roughness) come first; then the neighbours
/// of the two faces are put in correspondence (mirrored, since the faces meet face to
/// face; every turn tried, each neighbour paired by direction, extra faces left over), the
/// placement whose neighbourhood agrees best decides which sides meet, and on it come the
/// share of neighbours paired, their roughness, the shared-edge lengths, the sides along
/// them and the holes symmetric about the joint. docs/reassembly.md has the why.
///
/// Pure computation on BlockFeatures; deterministic; thread-compatible.

#include <array>
#include <compare>
#include <span>
#include <utility>
#include <vector>

#include "anascan/processing/reassembly/block_features.hpp"

namespace anascan::reassembly {

enum class Check : int {
    kNeighbourCount,      ///< |N(F)| = |N(F')|, read as the share of neighbours paired.
    kArea,                ///< w·h similar.
    kSize,                ///< Sides along corresponding edges similar.
    kRoughness,           ///< ρ similar.
    kNeighbourRoughness,  ///< Corresponding neighbours' ρ similar.
    kEdgeLengths,         ///< Corresponding shared edges similarly long.
    kHoles,               ///< Holes symmetric about the joint, of the same kind and size.
};
inline constexpr int kCheckCount = 7;
const char* to_string(Check check);

/// A face of a block: indices into the block list and the block's faces.
struct FaceRef {
    int block = 0;
    int face = 0;
    friend auto operator<=>(const FaceRef&, const FaceRef&) = default;
};

/// The score of one face pair with its breakdown.
struct FacePairScore {
    FaceRef a, b;
    double score = 0.0;                                ///< Σ weight · check score.
    std::array<double, kCheckCount> checks{};          ///< Each check's score, 0..1.
    std::vector<std::pair<int, int>> neighbour_pairs;  ///< Face ids of a ↔ b, best found.
    bool accepted = false;  ///< An expert accepted this pair (ranks first).

    bool passed(Check c) const { return checks[static_cast<int>(c)] >= 0.5; }
};

struct MatchConfig {
    double area_tolerance = 0.15;           ///< Relative area difference scoring 0.
    double size_tolerance_m = 0.04;         ///< Width/height difference scoring 0.
    double roughness_tolerance = 1.4;       ///< |ln(ρ/ρ')| scoring 0: a finish 4x rougher.
    double edge_length_tolerance_m = 0.06;  ///< Shared-edge length difference scoring 0.
    double hole_tolerance_m = 0.015;        ///< Hole position/size disagreement scoring 0.
    double hole_edge_reach_m = 0.025;  ///< A neighbour hole ending this near the edge opens on it.
    /// Neighbours pair when their directions about the joint face agree this well.
    double neighbour_angle_tolerance_deg = 30.0;
    std::array<double, kCheckCount> weights{1.0, 1.0, 1.0, 1.0, 1.0, 1.0, 3.0};
    std::array<bool, kCheckCount> enabled{true, true, true, true, true, true, true};
    int max_candidates = 50;  ///< Per face, best first.
};

/// Scores faces fa of a and fb of b (both matchable).
FacePairScore score_face_pair(const BlockFeatures& a, int fa, const BlockFeatures& b, int fb,
                              const MatchConfig& config);

enum class Decision { kAccepted, kRejected };

/// An expert's decision on a proposed pair, respected on every later run.
struct ExpertDecision {
    FaceRef a, b;
    Decision decision = Decision::kAccepted;
};

/// A face's ranked candidates, best first.
struct FaceProposals {
    FaceRef face;
    std::vector<FacePairScore> candidates;
};

struct MatchResult {
    std::vector<FaceProposals> per_face;  ///< Every face of every matchable block.
    /// Mutually best (or accepted) pairs: the block match graph's edges.
    std::vector<FacePairScore> match_graph;
    /// Consistent groups: connected blocks of the match graph, each sorted (size >= 2).
    std::vector<std::vector<int>> groups;
};

/// Scores every face pair across blocks; rejected pairs are dropped and accepted ones rank
/// first. Blocks that are not matchable take no part.
MatchResult match_blocks(std::span<const BlockFeatures> blocks,
                         std::span<const ExpertDecision> decisions, const MatchConfig& config);

}  // namespace anascan::reassembly
