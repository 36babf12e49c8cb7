// The neighbour-proposal figures of docs/reassembly.md in one process: for each seed of
// octagon-wall, block features of every fallen block (optionally with vertex noise), all
// face pairs matched, and the rank of the true neighbour of every true joint face
// (detected faces named by the truth: normal back in the block frame within 10 degrees).
// Usage: anascan_monument_figures NOISE_MM SEED... (seed 0: the section's own)
#include <cstdio>
#include <cstdlib>
#include <random>
#include <set>

#include "anascan/processing/reassembly/block_features.hpp"
#include "anascan/processing/reassembly/face_matching.hpp"
#include "anascan/sim/monument.hpp"

namespace {

using namespace anascan;
namespace ra = anascan::reassembly;

int true_face(const sim::MonumentBlock& b, const Eigen::Vector3d& n_ground) {
    const Eigen::Vector3d n = b.T_ground_block.linear().transpose() * n_ground;
    for (int f = 0; f < sim::kBlockFaceCount; ++f)
        if (n.dot(sim::face_normal(sim::BlockFace(f))) > std::cos(10.0 * M_PI / 180)) return f;
    return -1;
}

struct Tally {
    int faces = 0, top1 = 0, top3 = 0, missing = 0;
};

Tally evaluate(const sim::Monument& m, const std::vector<ra::BlockFeatures>& features,
               const ra::MatchResult& r) {
    std::set<std::pair<int, int>> joint_faces;  // (block, true face)
    std::set<std::pair<std::pair<int, int>, std::pair<int, int>>> truth;
    for (const sim::JointPair& j : m.joints) {
        const std::pair<int, int> a{j.a.block, int(j.a.face)}, b{j.b.block, int(j.b.face)};
        joint_faces.insert(a), joint_faces.insert(b);
        truth.insert({a, b}), truth.insert({b, a});
    }
    Tally t;
    for (const auto& jf : joint_faces) {
        int best = 0;  // 0: face not found; -1: not ranked.
        for (const ra::FaceProposals& p : r.per_face) {
            if (p.face.block != jf.first) continue;
            if (true_face(m.blocks[jf.first], features[jf.first].faces[p.face.face].normal) !=
                jf.second)
                continue;
            if (best == 0) best = -1;
            for (std::size_t k = 0; k < p.candidates.size(); ++k) {
                const ra::FaceRef o = p.candidates[k].b;
                const int of = true_face(m.blocks[o.block], features[o.block].faces[o.face].normal);
                if (truth.contains({jf, {o.block, of}})) {
                    if (best <= 0 || int(k) + 1 < best) best = int(k) + 1;
                    break;
                }
            }
        }
        ++t.faces;
        t.top1 += best == 1, t.top3 += best >= 1 && best <= 3, t.missing += best == 0;
    }
    return t;
}

}  // namespace

int main(int argc, char** argv) {
    if (argc < 3) {
        std::fprintf(stderr, "usage: %s NOISE_MM SEED...\n", argv[0]);
        return 2;
    }
    const double noise_m = std::atof(argv[1]) / 1000.0;
    std::vector<ra::MatchConfig> configs(1 + ra::kCheckCount);
    for (int c = 0; c < ra::kCheckCount; ++c) configs[1 + c].enabled[c] = false;
    std::vector<Tally> totals(configs.size());
    for (int a = 2; a < argc; ++a) {
        auto config = sim::named_monument("octagon-wall", std::strtoull(argv[a], nullptr, 10));
        auto m = sim::make_monument(*config);
        if (!m) return std::fprintf(stderr, "%s\n", m.error().message.c_str()), 1;
        std::vector<ra::BlockFeatures> features;
        std::mt19937 rng(7);
        std::normal_distribution<float> noise(0.0f, float(noise_m));
        for (const sim::MonumentBlock& b : m->blocks) {
            Mesh mesh = sim::transformed_mesh(sim::block_mesh(b), b.T_ground_block);
            if (noise_m > 0)
                for (auto& p : mesh.vertices.positions)
                    p += Eigen::Vector3f(noise(rng), noise(rng), noise(rng));
            features.push_back(ra::extract_block_features(mesh, {}));
        }
        for (std::size_t c = 0; c < configs.size(); ++c) {
            const Tally t = evaluate(*m, features, ra::match_blocks(features, {}, configs[c]));
            totals[c].faces += t.faces, totals[c].top1 += t.top1, totals[c].top3 += t.top3,
                totals[c].missing += t.missing;
            if (c == 0)
                std::printf("seed %s (%llu): %d joint faces, top-1 %d, top-3 %d, not found %d\n",
                            argv[a], (unsigned long long)config->seed, t.faces, t.top1, t.top3,
                            t.missing);
        }
    }
    for (std::size_t c = 0; c < configs.size(); ++c)
        std::printf("%-16s top-1 %5.1f%%  top-3 %5.1f%%  (%d joint faces, %d not found)\n",
                    c == 0 ? "all checks"
                           : (std::string("without ") + ra::to_string(ra::Check(c - 1))).c_str(),
                    100.0 * totals[c].top1 / totals[c].faces,
                    100.0 * totals[c].top3 / totals[c].faces, totals[c].faces, totals[c].missing);
    std::printf("random top-1: %.1f%%\n", 100.0 / (6.0 * 14.0));
    return 0;
}
