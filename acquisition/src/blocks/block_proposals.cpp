#include "anascan/acquisition/blocks/block_proposals.hpp"

#include <set>

#include "anascan/acquisition/blocks/block_features_file.hpp"

namespace anascan::acquisition {
namespace {

using nlohmann::json;

std::string block_of(const std::string& face) { return face.substr(0, face.rfind(':')); }

ProposalCandidate candidate_from(const std::string& face, const json& c) {
    ProposalCandidate out{.face = c.at("face").get<std::string>(),
                          .score = c.at("score").get<double>(),
                          .checks = c.contains("checks") ? c.at("checks").size() : 0,
                          .accepted = c.contains("accepted") && c.at("accepted").get<bool>()};
    if (c.contains("passed"))
        for (const json& name : c.at("passed")) out.passed.push_back(name.get<std::string>());
    if (c.contains("neighbour_pairs"))
        for (const json& n : c.at("neighbour_pairs"))
            out.neighbour_pairs.push_back(
                pair_name(block_of(face) + ":" + std::to_string(n.at(0).get<int>()),
                          block_of(out.face) + ":" + std::to_string(n.at(1).get<int>())));
    return out;
}

}  // namespace

Expected<BlockProposals> read_block_proposals(const std::filesystem::path& path) {
    auto j = read_json_file(path);
    if (!j) return fail(j.error());
    try {
        BlockProposals out{.features_dir = j->at("features_dir").get<std::string>()};
        for (const json& p : j->at("proposals")) {
            FaceProposals& face = out.faces.emplace_back();
            face.face = p.at("face").get<std::string>();
            for (const json& c : p.at("candidates"))
                face.candidates.push_back(candidate_from(face.face, c));
        }
        return out;
    } catch (const json::exception& e) {
        return fail(ErrorCode::kFormat,
                    path.string() + ": not a proposals file of blocks match: " + e.what());
    }
}

std::string pair_name(std::string a, std::string b) {
    if (b < a) std::swap(a, b);
    return a + "=" + b;
}

std::vector<std::string> accepted_pairs(const BlockProposals& proposals) {
    std::set<std::string> seen;
    std::vector<std::string> out;
    for (const FaceProposals& f : proposals.faces)
        for (const ProposalCandidate& c : f.candidates)
            if (c.accepted && seen.insert(pair_name(f.face, c.face)).second)
                out.push_back(pair_name(f.face, c.face));
    return out;
}

}  // namespace anascan::acquisition
