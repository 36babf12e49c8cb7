// anascan blocks match DIR --out proposals.json [--top K] [--disable CHECK]: every face
// pair of the blocks in DIR (ID.features.json) scored (method paper §5.2), a ranked
// proposal list per face with each check's score, the block match graph and its groups;
// the expert's decisions in DIR/decisions.json are respected.
// anascan blocks accept|reject PROPOSALS.json A:F B:G: records a decision there.
#include <spdlog/spdlog.h>

#include <algorithm>
#include <cstdio>
#include <filesystem>

#include "anascan/acquisition/blocks/block_features_file.hpp"
#include "commands.hpp"

namespace anascan::cli {
namespace {

using namespace anascan::acquisition;  // The blocks folder's files.

namespace ra = anascan::reassembly;
namespace fs = std::filesystem;
using nlohmann::json;

struct MatchOptions {
    std::string dir;
    std::string out;
    int top = 3;
    std::vector<std::string> disabled;
};

std::vector<NamedBlockFeatures> read_features_dir(const std::string& dir) {
    std::vector<fs::path> files;
    std::error_code ec;
    for (const auto& entry : fs::directory_iterator(dir, ec))
        if (entry.path().string().ends_with(".features.json")) files.push_back(entry.path());
    if (ec) fail_command({ErrorCode::kIo, dir + ": " + ec.message()});
    if (files.empty())
        fail_command({ErrorCode::kEmpty, dir + ": no *.features.json (run blocks features)"});
    std::sort(files.begin(), files.end());
    std::vector<NamedBlockFeatures> blocks;
    for (const fs::path& f : files) {
        auto j = read_json_file(f);
        if (!j) fail_command(j.error());
        auto b = block_features_from_json(*j, f.string());
        if (!b) fail_command(b.error());
        blocks.push_back(std::move(*b));
    }
    return blocks;
}

std::vector<std::string> ids_of(const std::vector<NamedBlockFeatures>& blocks) {
    std::vector<std::string> ids;
    for (const auto& b : blocks) ids.push_back(b.id);
    return ids;
}

fs::path decisions_path(const std::string& dir) { return fs::path(dir) / "decisions.json"; }

std::vector<ra::ExpertDecision> read_decisions(const std::string& dir,
                                               const std::vector<std::string>& ids) {
    std::vector<ra::ExpertDecision> out;
    if (!fs::exists(decisions_path(dir))) return out;
    auto j = read_json_file(decisions_path(dir));
    if (!j) fail_command(j.error());
    if (!j->is_object() || !j->value("decisions", json::array()).is_array()) {
        fail_command({ErrorCode::kFormat, decisions_path(dir).string() +
                                              ": not a decisions file (an object whose "
                                              "\"decisions\" is a list)"});
    }
    for (const json& d : j->value("decisions", json::array())) {
        if (!d.is_object() || !d.value("a", json()).is_string() ||
            !d.value("b", json()).is_string() || !d.value("decision", json("")).is_string()) {
            spdlog::warn("{}: ignoring a decision that is not {{a, b, decision}} strings",
                         decisions_path(dir).string());
            continue;
        }
        auto a = parse_face_ref(ids, d.value("a", std::string()));
        auto b = parse_face_ref(ids, d.value("b", std::string()));
        if (!a || !b) {
            spdlog::warn("{}: ignoring a decision: {}", decisions_path(dir).string(),
                         (!a ? a.error() : b.error()).message);
            continue;
        }
        out.push_back({*a, *b,
                       d.value("decision", "") == "rejected" ? ra::Decision::kRejected
                                                             : ra::Decision::kAccepted});
    }
    return out;
}

json candidate_json(const std::vector<NamedBlockFeatures>& blocks, const ra::FacePairScore& s) {
    json checks = json::object(), passed = json::array();
    for (int c = 0; c < ra::kCheckCount; ++c) {
        checks[ra::to_string(ra::Check(c))] = s.checks[c];
        if (s.passed(ra::Check(c))) passed.push_back(ra::to_string(ra::Check(c)));
    }
    json pairs = json::array();
    for (const auto& [x, y] : s.neighbour_pairs) pairs.push_back({x, y});
    return {{"face", face_label(blocks, s.b)},
            {"score", s.score},
            {"checks", checks},
            {"passed", passed},
            {"accepted", s.accepted},
            {"neighbour_pairs", pairs}};
}

json blocks_json(const std::vector<NamedBlockFeatures>& blocks) {
    json out = json::array();
    for (const auto& b : blocks) {
        json faces = json::array();
        for (const auto& f : b.features.faces)
            faces.push_back({{"id", f.id}, {"normal", {f.normal.x(), f.normal.y(), f.normal.z()}}});
        out.push_back({{"id", b.id},
                       {"status", ra::to_string(b.features.status)},
                       {"message", b.features.message},
                       {"faces", faces}});
    }
    return out;
}

void print_table(const std::vector<NamedBlockFeatures>& blocks, const ra::MatchResult& r, int top) {
    std::printf("%-12s %-12s %6s  %s\n", "face", "candidate", "score", "checks passed");
    for (const ra::FaceProposals& p : r.per_face) {
        for (int k = 0; k < std::min<int>(top, int(p.candidates.size())); ++k) {
            const ra::FacePairScore& s = p.candidates[k];
            std::string passed;
            for (int c = 0; c < ra::kCheckCount; ++c)
                if (s.passed(ra::Check(c)))
                    passed += std::string(passed.empty() ? "" : ",") + ra::to_string(ra::Check(c));
            std::printf("%-12s %-12s %6.2f  %s%s\n",
                        k == 0 ? face_label(blocks, p.face).c_str() : "",
                        face_label(blocks, s.b).c_str(), s.score, passed.c_str(),
                        s.accepted ? " (accepted)" : "");
        }
    }
}

void run_match(const MatchOptions& o) {
    const std::vector<NamedBlockFeatures> blocks = read_features_dir(o.dir);
    ra::MatchConfig config;
    for (const std::string& name : o.disabled) {
        bool found = false;
        for (int c = 0; c < ra::kCheckCount; ++c)
            if (name == ra::to_string(ra::Check(c))) config.enabled[c] = false, found = true;
        if (!found)
            fail_command({ErrorCode::kInvalidArgument, "--disable: no check '" + name + "'"});
    }
    std::vector<ra::BlockFeatures> features;
    for (const auto& b : blocks) {
        features.push_back(b.features);
        if (!b.features.matchable())
            spdlog::warn("block {} takes no part: {} ({})", b.id, ra::to_string(b.features.status),
                         b.features.message);
    }
    const auto decisions = read_decisions(o.dir, ids_of(blocks));
    const ra::MatchResult r = ra::match_blocks(features, decisions, config);
    json proposals = json::array(), groups = json::array();
    for (const ra::FaceProposals& p : r.per_face) {
        json candidates = json::array();
        for (const auto& s : p.candidates) candidates.push_back(candidate_json(blocks, s));
        proposals.push_back({{"face", face_label(blocks, p.face)}, {"candidates", candidates}});
    }
    for (const auto& g : r.groups) {
        json ids = json::array();
        for (int b : g) ids.push_back(blocks[b].id);
        groups.push_back(ids);
    }
    const json out{{"features_dir", fs::absolute(o.dir).string()},
                   {"blocks", blocks_json(blocks)},
                   {"proposals", proposals},
                   {"match_graph_edges", r.match_graph.size()},
                   {"groups", groups}};
    if (auto ok = write_json_file(o.out, out); !ok) fail_command(ok.error());
    print_table(blocks, r, o.top);
    std::printf("%zu faces of %zu blocks, %zu mutual best pairs, %zu groups; %zu decisions; %s\n",
                r.per_face.size(), blocks.size(), r.match_graph.size(), r.groups.size(),
                decisions.size(), o.out.c_str());
}

bool block_has_face(const json& block, int face) {
    for (const json& f : block.value("faces", json::array()))
        if (f.value("id", -1) == face) return true;
    return false;
}

void decide(const std::string& proposals, const std::string& a, const std::string& b, bool accept) {
    auto p = read_json_file(proposals);
    if (!p) fail_command(p.error());
    const std::string dir = p->value("features_dir", std::string());
    const json blocks = p->value("blocks", json::array());
    std::vector<std::string> ids;
    for (const json& blk : blocks) ids.push_back(blk.value("id", ""));
    std::vector<ra::FaceRef> refs;
    for (const std::string& text : {a, b}) {
        auto r = parse_face_ref(ids, text);
        if (!r) fail_command(r.error());
        if (!block_has_face(blocks[std::size_t(r->block)], r->face))
            fail_command({ErrorCode::kInvalidArgument,
                          proposals + ": block " + ids[std::size_t(r->block)] + " has no face " +
                              std::to_string(r->face) + " ('" + text + "')"});
        refs.push_back(*r);
    }
    if (refs[0].block == refs[1].block)
        fail_command({ErrorCode::kInvalidArgument,
                      "'" + a + "' and '" + b + "' are faces of one block, not neighbours"});
    json decisions = json{{"decisions", json::array()}};
    if (fs::exists(decisions_path(dir))) {
        auto d = read_json_file(decisions_path(dir));
        if (!d) fail_command(d.error());
        decisions = *d;
    }
    json& list = decisions["decisions"];
    for (auto it = list.begin(); it != list.end();)
        it = ((*it)["a"] == a && (*it)["b"] == b) || ((*it)["a"] == b && (*it)["b"] == a)
                 ? list.erase(it)
                 : it + 1;
    list.push_back({{"a", a}, {"b", b}, {"decision", accept ? "accepted" : "rejected"}});
    if (auto ok = write_json_file(decisions_path(dir), decisions); !ok) fail_command(ok.error());
    std::printf("%s %s = %s in %s (used by the next blocks match)\n",
                accept ? "accepted" : "rejected", a.c_str(), b.c_str(),
                decisions_path(dir).c_str());
}

/// A proposals or decisions file with values of the wrong type is named, not a crash.
void run_decide(const std::string& proposals, const std::string& a, const std::string& b,
                bool accept) {
    try {
        decide(proposals, a, b, accept);
    } catch (const json::exception& e) {
        fail_command({ErrorCode::kFormat, proposals +
                                              " (or its decisions.json): not a file of "
                                              "blocks match: " +
                                              e.what()});
    }
}

}  // namespace

void add_blocks_match_commands(CLI::App& blocks) {
    auto opts = std::make_shared<MatchOptions>();
    auto* cmd = blocks.add_subcommand("match", "Ranked neighbour proposals for every face");
    cmd->add_option("dir", opts->dir, "Folder of blocks features output")
        ->required()
        ->check(CLI::ExistingDirectory);
    cmd->add_option("--out", opts->out, "Proposals file (JSON)")->required();
    cmd->add_option("--top", opts->top, "Candidates per face in the table")
        ->check(CLI::PositiveNumber);
    cmd->add_option("--disable", opts->disabled,
                    "Leave a check out (ablation): neighbours, area, size, "
                    "roughness, nb-roughness, edges, holes");
    cmd->callback([opts] { run_match(*opts); });
    for (const bool accept : {true, false}) {
        auto refs = std::make_shared<std::array<std::string, 3>>();
        auto* d = blocks.add_subcommand(
            accept ? "accept" : "reject",
            accept ? "Accept a proposed face pair" : "Reject a proposed face pair");
        d->add_option("proposals", (*refs)[0], "Proposals file of blocks match")
            ->required()
            ->check(CLI::ExistingFile);
        d->add_option("a", (*refs)[1], "Face BLOCK:FACE")->required();
        d->add_option("b", (*refs)[2], "Face BLOCK:FACE")->required();
        d->callback([refs, accept] { run_decide((*refs)[0], (*refs)[1], (*refs)[2], accept); });
    }
}

}  // namespace anascan::cli
