// run_campaign's last stages: the match graph (stones) and the multi-view stage per stone.
#include <map>

#include "anascan/acquisition/campaign/campaign_results.hpp"
#include "campaign/campaign_json.hpp"
#include "campaign/job_steps.hpp"

namespace anascan::acquisition::campaign_steps {
namespace {

using nlohmann::json;

Expected<std::vector<RegisteredPair>> registered_pairs(const CampaignStore& store) {
    auto pairs = store.pairs();
    if (!pairs) return fail(pairs.error());
    std::vector<RegisteredPair> out;
    for (const CampaignPairRow& p : *pairs) {
        if (p.result_json.empty()) continue;
        const json j = json::parse(p.result_json);
        if (j.contains("error")) continue;
        out.push_back({static_cast<std::size_t>(p.source), static_cast<std::size_t>(p.target),
                       campaign_json::pair_from(j)});
    }
    return out;
}

/// The graph's warnings by scan id (only scans that carry one).
json warnings_json(const StoneGraph& graph) {
    json out = json::object();
    for (std::size_t i = 0; i < graph.warning_of_scan.size(); ++i) {
        if (!graph.warning_of_scan[i].empty()) out[std::to_string(i)] = graph.warning_of_scan[i];
    }
    return out;
}

/// The stored graph warnings by scan (empty before the graph stage).
Expected<std::map<std::int64_t, std::string>> stored_warnings(const CampaignStore& store,
                                                              std::size_t scan_count) {
    auto graph = store.value("graph");
    if (!graph) return fail(graph.error());
    auto warnings = read_graph_warnings(graph->value_or(""), scan_count);
    if (!warnings) return fail(campaign_json::damaged(store, "", warnings.error()));
    return warnings;
}

std::string warning_of(const std::map<std::int64_t, std::string>& warnings, std::int64_t id) {
    const auto it = warnings.find(id);
    return it == warnings.end() ? std::string() : it->second;
}

Expected<void> graph_stage(StageRun& run, CampaignStore& store,
                           const std::vector<CampaignScanRow>& scans,
                           const CampaignConfig& config) {
    auto done = store.value("graph");
    if (!done) return fail(done.error());
    run.report.stages.push_back({"stones", *done ? 1u : 0u, *done ? 0u : 1u});
    if (*done) return {};
    auto pairs = registered_pairs(store);
    if (!pairs) return fail(pairs.error());
    std::vector<PreparedSummary> summaries;
    for (const CampaignScanRow& scan : scans) summaries.push_back(summary_of(scan));
    const StoneGraph graph = find_stones(summaries, *pairs, config);
    std::vector<CampaignStoneRow> rows;
    for (std::size_t s = 0; s < graph.stones.size(); ++s) {
        CampaignStoneRow row{.id = static_cast<std::int64_t>(s)};
        for (std::size_t i : graph.stones[s]) row.scans.push_back(static_cast<std::int64_t>(i));
        rows.push_back(row);
    }
    std::size_t verified = 0;
    for (const RegisteredPair& p : *pairs) verified += p.result.verified;
    const json figures = {{"stones", rows.size()},
                          {"registered_pairs", pairs->size()},
                          {"verified_pairs", verified},
                          {"relative_gated_pairs", graph.relative_gated_pairs},
                          {"triangle_cut_pairs", graph.triangle_cut_pairs},
                          {"cycle_cut_pairs", graph.cycle_cut_pairs},
                          {"warnings", warnings_json(graph)}};
    if (run.progress) run.progress({.stage = "stones", .done = 1, .total = 1});
    return store.set_stones(rows, figures.dump());
}

Expected<void> multiview_stage(StageRun& run, CampaignStore& store,
                               const std::vector<CampaignScanRow>& scans) {
    auto stones = store.stones();
    if (!stones) return fail(stones.error());
    auto warnings = stored_warnings(store, scans.size());
    if (!warnings) return fail(warnings.error());
    std::vector<CampaignTask> tasks;
    for (const CampaignStoneRow& stone : *stones) {
        if (!stone.result_json.empty()) continue;
        json list = json::array();
        double points = 0.0;
        for (std::int64_t id : stone.scans) {
            list.push_back({{"id", id},
                            {"prepared", store.prepared_file(id).string()},
                            {"graph_warning", warning_of(*warnings, id)}});
            points += static_cast<double>(summary_of(scans[static_cast<std::size_t>(id)]).points);
        }
        tasks.push_back({CampaignTaskKind::kStone, stone.id, json{{"scans", list}}.dump(),
                         points * static_cast<double>(stone.scans.size())});
    }
    const std::size_t done = stones->size() - tasks.size();
    return run_stage(run, "multiview", std::move(tasks), done,
                     [&](CampaignTaskResult r) -> Expected<void> {
                         return store.save_stone_result(r.id, r.output_json);
                     });
}

}  // namespace

Expected<void> stone_stages(StageRun& run, CampaignStore& store,
                            const std::vector<CampaignScanRow>& scans,
                            const CampaignConfig& config) {
    if (auto ok = graph_stage(run, store, scans, config); !ok) return ok;
    return multiview_stage(run, store, scans);
}

}  // namespace anascan::acquisition::campaign_steps
