// Ranked neighbour proposals, expert decisions and the block match graph (paper §5.2):
// every face pair across blocks scored, each face's candidates ranked, mutually best pairs
// joined into groups of consistent blocks.
#include <algorithm>
#include <numeric>

#include "anascan/processing/reassembly/face_matching.hpp"

namespace anascan::reassembly {
namespace {

const ExpertDecision* decision_of(std::span<const ExpertDecision> decisions, FaceRef a, FaceRef b) {
    for (const ExpertDecision& d : decisions)
        if ((d.a == a && d.b == b) || (d.a == b && d.b == a)) return &d;
    return nullptr;
}

bool ranks_before(const FacePairScore& x, const FacePairScore& y) {
    if (x.accepted != y.accepted) return x.accepted;
    if (x.score != y.score) return x.score > y.score;
    return std::tie(x.b.block, x.b.face) < std::tie(y.b.block, y.b.face);
}

FacePairScore swapped(FacePairScore s) {
    std::swap(s.a, s.b);
    for (auto& [x, y] : s.neighbour_pairs) std::swap(x, y);
    return s;
}

// Connected components of the blocks over the match graph's edges.
std::vector<std::vector<int>> groups_of(std::size_t num_blocks,
                                        const std::vector<FacePairScore>& graph) {
    std::vector<int> parent(num_blocks);
    std::iota(parent.begin(), parent.end(), 0);
    auto find = [&](int i) {
        while (parent[i] != i) i = parent[i] = parent[parent[i]];
        return i;
    };
    for (const FacePairScore& e : graph) parent[find(e.a.block)] = find(e.b.block);
    std::vector<std::vector<int>> by_root(num_blocks);
    for (std::size_t i = 0; i < num_blocks; ++i) by_root[find(int(i))].push_back(int(i));
    std::vector<std::vector<int>> out;
    for (auto& g : by_root)
        if (g.size() >= 2) out.push_back(std::move(g));
    return out;
}

}  // namespace

MatchResult match_blocks(std::span<const BlockFeatures> blocks,
                         std::span<const ExpertDecision> decisions, const MatchConfig& config) {
    MatchResult out;
    std::vector<std::vector<std::size_t>> slot(blocks.size());  // per_face index of a face.
    for (std::size_t bi = 0; bi < blocks.size(); ++bi) {
        if (!blocks[bi].matchable()) continue;
        for (std::size_t f = 0; f < blocks[bi].faces.size(); ++f) {
            slot[bi].push_back(out.per_face.size());
            out.per_face.push_back({.face = {int(bi), int(f)}});
        }
    }
    for (std::size_t bi = 0; bi < blocks.size(); ++bi) {
        for (std::size_t bj = bi + 1; bj < blocks.size(); ++bj) {
            if (slot[bi].empty() || slot[bj].empty()) continue;
            for (std::size_t fa = 0; fa < slot[bi].size(); ++fa) {
                for (std::size_t fb = 0; fb < slot[bj].size(); ++fb) {
                    FacePairScore s =
                        score_face_pair(blocks[bi], int(fa), blocks[bj], int(fb), config);
                    s.a = {int(bi), int(fa)};
                    s.b = {int(bj), int(fb)};
                    const ExpertDecision* d = decision_of(decisions, s.a, s.b);
                    if (d != nullptr && d->decision == Decision::kRejected) continue;
                    s.accepted = d != nullptr;
                    out.per_face[slot[bj][fb]].candidates.push_back(swapped(s));
                    out.per_face[slot[bi][fa]].candidates.push_back(std::move(s));
                }
            }
        }
    }
    for (FaceProposals& p : out.per_face) {
        std::sort(p.candidates.begin(), p.candidates.end(), ranks_before);
        if (p.candidates.size() > std::size_t(config.max_candidates))
            p.candidates.resize(std::size_t(config.max_candidates));
    }
    // Match graph: accepted pairs, and pairs that are each other's first candidate.
    for (const FaceProposals& p : out.per_face) {
        if (p.candidates.empty()) continue;
        const FacePairScore& top = p.candidates.front();
        if (top.a > top.b) continue;  // Each pair once.
        const FaceProposals& other = out.per_face[slot[top.b.block][top.b.face]];
        if (top.accepted || (!other.candidates.empty() && other.candidates.front().b == top.a))
            out.match_graph.push_back(top);
    }
    out.groups = groups_of(blocks.size(), out.match_graph);
    return out;
}

}  // namespace anascan::reassembly
