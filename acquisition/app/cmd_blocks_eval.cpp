// anascan blocks eval PROPOSALS.json --truth DIR/truth.json [--json]: for every true joint
// face of the simulated monument, the rank of its true neighbour face in its proposal
// list; the top-1 and top-3 shares, and how many wrong pairs outscore the lowest true one.
// Detected faces are named by the truth: a face's normal, taken back into the block frame
// by T_ground_block, within 10 degrees of a block axis.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <map>
#include <set>

#include "anascan/acquisition/blocks/block_features_file.hpp"
#include "commands.hpp"

namespace anascan::cli {
namespace {

using namespace anascan::acquisition;  // The blocks folder's files.

using nlohmann::json;
using FaceKey = std::pair<std::string, std::string>;  // Block id, true face name ("+x").

struct EvalOptions {
    std::string proposals;
    std::string truth;
    bool as_json = false;
};

std::string true_face_name(const Eigen::Matrix3d& R_ground_block, const Eigen::Vector3d& n_ground) {
    static const char* kNames[6] = {"+x", "-x", "+y", "-y", "+z", "-z"};
    const Eigen::Vector3d n = R_ground_block.transpose() * n_ground.normalized();
    for (int f = 0; f < 6; ++f) {
        Eigen::Vector3d axis = Eigen::Vector3d::Zero();
        axis[f / 2] = f % 2 == 0 ? 1.0 : -1.0;
        if (n.dot(axis) > std::cos(10.0 * M_PI / 180.0)) return kNames[f];
    }
    return "";
}

// Detected face label ("c0b1:3") -> true face key, for every face the truth can name.
std::map<std::string, FaceKey> name_faces(const json& proposals, const json& truth) {
    std::map<std::string, Eigen::Matrix3d> rotation;
    for (const json& b : truth.at("blocks")) {
        Eigen::Matrix3d R;
        for (int r = 0; r < 3; ++r)
            for (int c = 0; c < 3; ++c) R(r, c) = b.at("T_ground_block").at(r).at(c).get<double>();
        rotation[b.at("id").get<std::string>()] = R;
    }
    std::map<std::string, FaceKey> out;
    for (const json& b : proposals.at("blocks")) {
        const std::string id = b.at("id").get<std::string>();
        if (!rotation.contains(id)) continue;
        for (const json& f : b.at("faces")) {
            const Eigen::Vector3d n(f.at("normal").at(0).get<double>(),
                                    f.at("normal").at(1).get<double>(),
                                    f.at("normal").at(2).get<double>());
            if (std::string name = true_face_name(rotation[id], n); !name.empty())
                out[id + ":" + std::to_string(f.at("id").get<int>())] = {id, name};
        }
    }
    return out;
}

struct JointFaceRank {
    FaceKey face;
    std::string kind;
    int rank = 0;  ///< 1 = first; 0 = the face was not found; -1 = not among the candidates.
    double score = 0.0;
};

// The true joints: each joint face's true partners and the joint's kind.
struct TrueJoints {
    std::map<FaceKey, std::set<FaceKey>> partners;
    std::map<FaceKey, std::string> kind;
};

TrueJoints read_joints(const json& truth) {
    TrueJoints t;
    for (const json& j : truth.at("joints")) {
        const FaceKey a{j.at("a").at("block"), j.at("a").at("face")},
            b{j.at("b").at("block"), j.at("b").at("face")};
        t.partners[a].insert(b), t.partners[b].insert(a);
        t.kind[a] = t.kind[b] = j.at("kind").get<std::string>();
    }
    return t;
}

// Ranks of the true partners in the proposal lists, and the scores of the wrong pairs.
struct Ranking {
    std::vector<JointFaceRank> ranks;
    std::map<std::set<std::string>, double> wrong;  ///< Unordered wrong pair -> score.
};

void rank_one_list(const json& p, const std::map<std::string, FaceKey>& names, TrueJoints& t,
                   Ranking& out) {
    const std::string label = p.at("face").get<std::string>();
    const auto self = names.find(label);
    const auto& cands = p.at("candidates");
    for (std::size_t k = 0; k < cands.size(); ++k) {
        const std::string other = cands[k].at("face").get<std::string>();
        const auto it = names.find(other);
        const bool is_true = self != names.end() && it != names.end() &&
                             t.partners.contains(self->second) &&
                             t.partners[self->second].contains(it->second);
        if (!is_true) {
            out.wrong[{label, other}] = cands[k].at("score").get<double>();
            continue;
        }
        for (JointFaceRank& r : out.ranks)
            if (r.face == self->second && (r.rank <= 0 || int(k) + 1 < r.rank))
                r.rank = int(k) + 1, r.score = cands[k].at("score").get<double>();
        break;
    }
    if (self == names.end()) return;
    for (JointFaceRank& r : out.ranks)
        if (r.face == self->second && r.rank == 0) r.rank = -1;  // Found, not ranked.
}

Ranking rank_true_neighbours(const json& proposals, const json& truth) {
    const std::map<std::string, FaceKey> names = name_faces(proposals, truth);
    TrueJoints t = read_joints(truth);
    Ranking out;
    for (const auto& [face, ps] : t.partners) out.ranks.push_back({face, t.kind[face]});
    for (const json& p : proposals.at("proposals")) rank_one_list(p, names, t, out);
    return out;
}

json summarise(const Ranking& ranking, std::size_t block_count) {
    const std::vector<JointFaceRank>& ranks = ranking.ranks;
    int top1 = 0, top3 = 0, missing = 0, top1_vertical = 0, vertical = 0;
    double lowest_true = 1e300;
    for (const JointFaceRank& r : ranks) {
        top1 += r.rank == 1, top3 += r.rank >= 1 && r.rank <= 3, missing += r.rank == 0;
        vertical += r.kind == "vertical", top1_vertical += r.kind == "vertical" && r.rank == 1;
        if (r.rank >= 1) lowest_true = std::min(lowest_true, r.score);
    }
    int wrong_above = 0;
    for (const auto& [pair, score] : ranking.wrong) wrong_above += score > lowest_true;
    const double n = std::max<double>(1.0, double(ranks.size()));
    const std::size_t beds = ranks.size() - std::size_t(vertical);
    json out{{"joint_faces", ranks.size()},
             {"top1_share", top1 / n},
             {"top3_share", top3 / n},
             {"faces_not_found", missing},
             {"vertical_top1_share", vertical ? double(top1_vertical) / vertical : 0.0},
             {"bed_top1_share", beds ? double(top1 - top1_vertical) / double(beds) : 0.0},
             {"wrong_pairs_above_lowest_true", wrong_above},
             {"random_top1", 1.0 / (6.0 * double(block_count))}};
    json per = json::array();
    for (const JointFaceRank& r : ranks)
        per.push_back({{"block", r.face.first},
                       {"face", r.face.second},
                       {"kind", r.kind},
                       {"rank", r.rank},
                       {"score", r.score}});
    out["ranks"] = per;
    return out;
}

void print_table(const Ranking& ranking, const json& out) {
    for (const JointFaceRank& r : ranking.ranks)
        std::printf("%-6s %-3s %-9s rank %s\n", r.face.first.c_str(), r.face.second.c_str(),
                    r.kind.c_str(),
                    r.rank > 0 ? std::to_string(r.rank).c_str()
                               : (r.rank == 0 ? "face not found" : "not ranked"));
    std::printf(
        "%zu true joint faces: top-1 %.1f%%, top-3 %.1f%% (vertical top-1 %.1f%%, bed top-1 "
        "%.1f%%); %d faces not found; %d wrong pairs above the lowest true pair; random top-1 "
        "%.1f%%\n",
        ranking.ranks.size(), 100 * out["top1_share"].get<double>(),
        100 * out["top3_share"].get<double>(), 100 * out["vertical_top1_share"].get<double>(),
        100 * out["bed_top1_share"].get<double>(), out["faces_not_found"].get<int>(),
        out["wrong_pairs_above_lowest_true"].get<int>(), 100 * out["random_top1"].get<double>());
}

void run_eval(const EvalOptions& o) {
    if (std::filesystem::is_directory(o.proposals))
        return run_assembly_eval(o.proposals, o.truth, o.as_json);
    auto proposals = read_json_file(o.proposals);
    if (!proposals) fail_command(proposals.error());
    auto truth = read_json_file(o.truth);
    if (!truth) fail_command(truth.error());
    try {
        const Ranking ranking = rank_true_neighbours(*proposals, *truth);
        const json out = summarise(ranking, truth->at("blocks").size());
        if (o.as_json)
            std::printf("%s\n", out.dump(1).c_str());
        else
            print_table(ranking, out);
    } catch (const json::exception& e) {
        fail_command({ErrorCode::kFormat, o.proposals + " / " + o.truth + ": " + e.what()});
    }
}

}  // namespace

void add_blocks_eval_command(CLI::App& blocks) {
    auto opts = std::make_shared<EvalOptions>();
    auto* cmd =
        blocks.add_subcommand("eval", "Ranks of the true neighbours (simulated monument truth)");
    cmd->add_option("proposals", opts->proposals,
                    "Proposals of blocks match, or an ASSEMBLY/ folder of blocks assemble")
        ->required()
        ->check(CLI::ExistingPath);
    cmd->add_option("--truth", opts->truth, "truth.json of sim export-monument")
        ->required()
        ->check(CLI::ExistingFile);
    cmd->add_flag("--json", opts->as_json, "JSON on stdout");
    cmd->callback([opts] { run_eval(*opts); });
}

}  // namespace anascan::cli
