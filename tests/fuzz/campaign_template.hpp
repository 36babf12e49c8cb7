#pragma once
// A small finished campaign written through the store's own API, in the stored formats the
// job writes: scans 0-3 described (30-point prepared clouds), scan 4 not used; four candidate
// pairs, three verified and one whose registration failed; the match graph with one warning;
// one stone (scans 0-2) refined, scan 2 not placed. Shared by the campaign store's fuzz
// harness and its damage tests.
#include <cstdlib>
#include <filesystem>
#include <string>
#include <vector>

#include "anascan/acquisition/campaign/campaign_store.hpp"
#include "anascan/processing/io/ply.hpp"

namespace anascan::test {

inline void campaign_template_require(bool ok) {
    if (!ok) std::abort();
}

inline std::string campaign_template_pose(double tx) {
    return "[1,0,0," + std::to_string(tx) + ",0,1,0,0,0,0,1,0,0,0,0,1]";
}

inline std::string campaign_template_summary(int scan) {
    return R"({"points":30,"spacing_m":0.002,"centre_m":[0.01,0.02,)" + std::to_string(scan) +
           R"(],"diagonal_m":0.1,"position_hash":)" + std::to_string(1000 + scan) +
           R"(,"normals_estimated":true,"problem":""})";
}

inline std::string campaign_template_pair(bool verified) {
    if (!verified) return R"({"error":"unreadable scan: gone"})";
    return R"({"status":"success","status_code":0,"verified":true,"T_target_source":)" +
           campaign_template_pose(0.05) +
           R"(,"rms_m":0.0003,"overlap":0.6,"target_spacing_m":0.002,"slide_ambiguous":false,"time_s":0.4})";
}

inline std::string campaign_template_stone() {
    std::string scans;
    for (int id = 0; id < 3; ++id) {
        scans += std::string(id ? "," : "") + R"({"id":)" + std::to_string(id) + R"(,"placed":)" +
                 (id < 2 ? "true" : "false") + R"(,"pose":)" + campaign_template_pose(0.05 * id) +
                 R"(,"reason":)" + (id < 2 ? R"("")" : R"("no verified link")") + R"(,"warning":)" +
                 (id == 1 ? R"("match graph: a doubt")" : R"("")") + "}";
    }
    return R"({"scans":[)" + scans +
           R"(],"placed":2,"links":1,"verified_pairs":1,"multiview":"converged","reference":0,"time_s":1.5})";
}

inline void write_campaign_template(const std::filesystem::path& dir) {
    std::vector<std::string> files;
    for (int i = 0; i < 5; ++i) files.push_back("/nonexistent/scan_" + std::to_string(i) + ".ply");
    auto made = acquisition::CampaignStore::create(dir, files);
    campaign_template_require(bool(made));
    acquisition::CampaignStore& store = **made;
    for (int i = 0; i < 5; ++i) {
        acquisition::CampaignScanRow row{.id = i, .file = files[std::size_t(i)]};
        row.state = i < 4 ? "described" : "unusable";
        row.problem = i < 4 ? "" : "unreadable scan: gone";
        row.summary_json = i < 4 ? campaign_template_summary(i) : "";
        row.keys = {std::uint64_t(7 + i), std::uint64_t(99)};
        campaign_template_require(bool(store.save_scan(row)));
        if (i == 4) continue;
        PointCloud cloud;
        for (int p = 0; p < 30; ++p) cloud.positions.emplace_back(0.002f * float(p), 0.f, float(i));
        campaign_template_require(bool(io::write_ply(store.prepared_file(i), cloud)));
    }
    campaign_template_require(
        bool(store.set_candidates({{.source = 1, .target = 0, .similarity = 0.9},
                                   {.source = 2, .target = 1, .similarity = 0.8},
                                   {.source = 3, .target = 2, .similarity = 0.5},
                                   {.source = 3, .target = 0, .similarity = 0.4}})));
    campaign_template_require(bool(store.set_value("candidates", R"({"scans":4,"pairs":4})")));
    for (auto [s, t, ok] : {std::tuple{1, 0, true}, {2, 1, true}, {3, 2, true}, {3, 0, false}})
        campaign_template_require(bool(store.save_pair_result(s, t, campaign_template_pair(ok))));
    campaign_template_require(bool(store.set_stones(
        {{.id = 0, .scans = {0, 1, 2}}, {.id = 1, .scans = {3}}},
        R"({"stones":2,"registered_pairs":4,"verified_pairs":3,"warnings":{"1":"a doubt"}})")));
    campaign_template_require(bool(store.save_stone_result(0, campaign_template_stone())));
    campaign_template_require(bool(store.set_value("config", R"({"candidates_per_scan":8})")));
}

}  // namespace anascan::test
