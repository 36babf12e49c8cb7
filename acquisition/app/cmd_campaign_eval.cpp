// anascan campaign eval DIR --truth TRUTH.json (hidden): a campaign's result against the
// truth of `sim campaign`: scans placed, in the wrong stone (with and without a warning),
// pose errors, and the recall of the candidate and verified pairs among the truly
// overlapping pairs.
#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <map>
#include <nlohmann/json.hpp>
#include <set>

#include "anascan/processing/io/ply.hpp"
#include "anascan/processing/spatial/kdtree.hpp"
#include "campaign_cli.hpp"
#include "commands.hpp"

namespace anascan::cli {
namespace {

namespace fs = std::filesystem;
using acquisition::CampaignStore;
using nlohmann::json;

struct EvalOptions {
    std::string dir, truth;
    double min_overlap = 0.3;
};

struct TruthScan {
    int stone = -1;
    Pose T_stone_scan = Pose::Identity();
};

Pose pose_from(const json& rows) {
    Pose T = Pose::Identity();
    for (int i = 0; i < 3; ++i)
        for (int j = 0; j < 4; ++j) T.matrix()(i, j) = rows[static_cast<std::size_t>(4 * i + j)];
    return T;
}

/// Truth per campaign scan (by file name).
std::vector<TruthScan> read_truth(const std::string& path,
                                  const std::vector<acquisition::CampaignScanRow>& scans) {
    std::ifstream in(path);
    if (!in) throw CommandFailed(path + ": cannot read the truth file");
    const json truth = json::parse(in, nullptr, false);
    if (truth.is_discarded()) throw CommandFailed(path + ": not JSON");
    std::map<std::string, TruthScan> by_name;
    for (const json& s : truth["scans"]) {
        by_name[s["file"].get<std::string>()] = {s["stone"].get<int>(),
                                                 pose_from(s["T_stone_scan"])};
    }
    std::vector<TruthScan> out;
    for (const auto& s : scans) {
        const auto it = by_name.find(fs::path(s.file).filename().string());
        out.push_back(it == by_name.end() ? TruthScan{} : it->second);
    }
    return out;
}

struct PlacementFigures {
    std::size_t truth_scans = 0, placed = 0, wrong = 0, wrong_silent = 0, split_stones = 0;
    double max_rotation_deg = 0.0, max_translation_mm = 0.0;
};

double rotation_deg(const Eigen::Matrix3d& R) {
    return Eigen::AngleAxisd(R).angle() * 180.0 / M_PI;
}

/// One found stone against the truth stone most of its placed scans belong to.
void eval_stone(const json& result, const std::vector<TruthScan>& truth,
                const std::vector<Eigen::Vector3d>& centre, std::set<int>& seen,
                PlacementFigures& f) {
    std::map<int, int> votes;
    for (const json& s : result["scans"]) {
        if (s["placed"].get<bool>()) ++votes[truth[s["id"].get<std::size_t>()].stone];
    }
    if (votes.empty()) return;
    const int stone = std::max_element(votes.begin(), votes.end(), [](auto& a, auto& b) {
                          return a.second < b.second;
                      })->first;
    f.split_stones += !seen.insert(stone).second;
    std::optional<Pose> E;  // T_truth_found, from the first placed scan of the stone.
    for (const json& s : result["scans"]) {
        if (!s["placed"].get<bool>()) continue;
        const auto id = s["id"].get<std::size_t>();
        if (truth[id].stone != stone) {
            ++f.wrong;
            f.wrong_silent += s["warning"].get<std::string>().empty();
            continue;
        }
        ++f.placed;
        const Pose T_found = pose_from(s["pose"]);
        if (!E) E = truth[id].T_stone_scan * T_found.inverse();
        const Pose D = truth[id].T_stone_scan.inverse() * (*E * T_found);
        f.max_rotation_deg = std::max(f.max_rotation_deg, rotation_deg(D.linear()));
        const Eigen::Vector3d c = centre[id];
        f.max_translation_mm = std::max(
            f.max_translation_mm, 1e3 * ((*E * T_found) * c - truth[id].T_stone_scan * c).norm());
    }
}

PointCloud stone_frame_cloud(const CampaignStore& store, std::int64_t id, const Pose& T) {
    auto ply = io::read_ply(store.prepared_file(id));
    return ply ? transformed(ply->cloud, T) : PointCloud{};
}

/// Fraction of the smaller cloud's points within 3 spacings of the other one.
double overlap(const PointCloud& a, const PointCloud& b, double spacing_m) {
    const PointCloud& small = a.size() <= b.size() ? a : b;
    const PointCloud& large = a.size() <= b.size() ? b : a;
    if (small.empty() || large.empty()) return 0.0;
    std::vector<Eigen::Vector3f> target;
    for (const auto& p : large.positions)
        target.push_back((large.origin_m + p.cast<double>()).cast<float>());
    const KdTree tree(target);
    std::size_t near = 0;
    Neighbor n;
    for (const auto& p : small.positions) {
        const Eigen::Vector3f q = (small.origin_m + p.cast<double>()).cast<float>();
        near += tree.nearest_within(q, static_cast<float>(3.0 * spacing_m), n);
    }
    return static_cast<double>(near) / static_cast<double>(small.size());
}

void eval_pairs(const CampaignStore& store, const std::vector<acquisition::CampaignScanRow>& scans,
                const std::vector<TruthScan>& truth, double min_overlap) {
    std::map<std::pair<std::int64_t, std::int64_t>, bool> candidates;  // → verified.
    std::size_t candidate_count = 0;
    auto pairs = store.pairs();
    if (!pairs) fail_command(pairs.error());
    for (const auto& p : *pairs) {
        ++candidate_count;
        candidates[{p.source, p.target}] =
            !p.result_json.empty() && json::parse(p.result_json).value("verified", false);
    }
    std::size_t overlapping = 0, found = 0, verified = 0, usable = 0;
    for (std::size_t s = 0; s < scans.size(); ++s) {
        if (scans[s].state != "described") continue;
        ++usable;
        const PointCloud a =
            stone_frame_cloud(store, static_cast<std::int64_t>(s), truth[s].T_stone_scan);
        const double sa = json::parse(scans[s].summary_json).value("spacing_m", 0.0);
        for (std::size_t t = 0; t < s; ++t) {
            if (scans[t].state != "described" || truth[s].stone < 0 ||
                truth[s].stone != truth[t].stone)
                continue;
            const PointCloud b =
                stone_frame_cloud(store, static_cast<std::int64_t>(t), truth[t].T_stone_scan);
            const double sb = json::parse(scans[t].summary_json).value("spacing_m", 0.0);
            if (overlap(a, b, std::max(sa, sb)) < min_overlap) continue;
            ++overlapping;
            const auto it =
                candidates.find({static_cast<std::int64_t>(s), static_cast<std::int64_t>(t)});
            found += it != candidates.end();
            verified += it != candidates.end() && it->second;
        }
    }
    const std::size_t all = usable * (usable > 0 ? usable - 1 : 0) / 2;
    std::printf(
        "pairs: %zu truly overlapping (>= %.0f %%), %zu candidates (%.2f %% of %zu), "
        "recall %.1f %% (%zu), verified %.1f %% (%zu)\n",
        overlapping, 100.0 * min_overlap, candidate_count,
        all ? 100.0 * static_cast<double>(candidate_count) / static_cast<double>(all) : 0.0, all,
        overlapping ? 100.0 * static_cast<double>(found) / static_cast<double>(overlapping) : 0.0,
        found,
        overlapping ? 100.0 * static_cast<double>(verified) / static_cast<double>(overlapping)
                    : 0.0,
        verified);
}

void run_eval(const EvalOptions& o) {
    auto store = CampaignStore::open(o.dir, true);
    if (!store) fail_command(store.error());
    auto scans = (*store)->scans();
    if (!scans) fail_command(scans.error());
    const std::vector<TruthScan> truth = read_truth(o.truth, *scans);
    std::vector<Eigen::Vector3d> centre;
    PlacementFigures f;
    for (std::size_t i = 0; i < scans->size(); ++i) {
        const auto& s = (*scans)[i];
        centre.push_back(
            s.summary_json.empty()
                ? Eigen::Vector3d::Zero()
                : Eigen::Vector3d(json::parse(s.summary_json)["centre_m"][0].get<double>(),
                                  json::parse(s.summary_json)["centre_m"][1].get<double>(),
                                  json::parse(s.summary_json)["centre_m"][2].get<double>()));
        f.truth_scans += truth[i].stone >= 0;
    }
    std::set<int> seen;
    auto stones = (*store)->stones();
    if (!stones) fail_command(stones.error());
    for (const auto& stone : *stones) {
        if (!stone.result_json.empty())
            eval_stone(json::parse(stone.result_json), truth, centre, seen, f);
    }
    std::printf(
        "placed %zu of %zu stone scans (%.1f %%); wrong stone %zu (without a warning %zu); "
        "stones split %zu\n",
        f.placed, f.truth_scans,
        f.truth_scans ? 100.0 * static_cast<double>(f.placed) / static_cast<double>(f.truth_scans)
                      : 0.0,
        f.wrong, f.wrong_silent, f.split_stones);
    std::printf("max pose error: %.3f deg, %.3f mm (at the scan centres)\n", f.max_rotation_deg,
                f.max_translation_mm);
    eval_pairs(**store, *scans, truth, o.min_overlap);
}

}  // namespace

void add_campaign_eval_command(CLI::App& campaign) {
    auto o = std::make_shared<EvalOptions>();
    auto* cmd =
        campaign.add_subcommand("eval", "Compare a campaign with the truth of `sim campaign`")
            ->group("");
    cmd->add_option("dir", o->dir, "Campaign folder")->required();
    cmd->add_option("--truth", o->truth, "truth.json of `sim campaign`")->required();
    cmd->add_option("--min-overlap", o->min_overlap, "Truly overlapping: at least this fraction");
    cmd->callback([o] { run_eval(*o); });
}

}  // namespace anascan::cli
