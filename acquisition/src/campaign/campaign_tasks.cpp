// The campaign's tasks as run on any rank: read the files a task names, run the pure stage,
// return JSON (and the descriptor keys as bytes).
#include <cstring>

#include "anascan/acquisition/campaign/campaign_job.hpp"
#include "anascan/processing/io/ply.hpp"
#include "campaign/campaign_json.hpp"

namespace anascan::acquisition {
namespace {

using nlohmann::json;

Expected<PointCloud> read_cloud(const std::string& path) {
    auto ply = io::read_ply(path);
    if (!ply) return fail(ply.error());
    return std::move(ply->cloud);
}

/// A pair's result as stored (campaign_json::pair_from reads it).
json pair_json(const CampaignPairResult& r) {
    return {{"status", std::string(to_string(r.status))},
            {"status_code", static_cast<int>(r.status)},
            {"verified", r.verified},
            {"T_target_source", campaign_json::pose(r.T_target_source)},
            {"rms_m", r.rms_m},
            {"overlap", r.overlap_fraction},
            {"target_spacing_m", r.target_spacing_m},
            {"slide_ambiguous", r.slide_ambiguous},
            {"time_s", r.time_s}};
}

/// The campaign's own prepared cloud cannot be read: the job stops (the row is not marked),
/// `campaign check --repair` sets the scan back so that it is prepared again.
json store_error(const Error& e) {
    return {{"store_error", "cannot read the prepared scan: " + e.message +
                                " (run `anascan campaign check --repair`, then register again)"}};
}

json prepare(const json& in, const CampaignConfig& config) {
    auto cloud = read_cloud(in.at("file").get<std::string>());
    if (!cloud) return {{"error", "unreadable scan: " + cloud.error().message}};
    const PreparedSummary summary = prepare_campaign_scan(*cloud, config);
    if (summary.problem.empty()) {
        if (auto ok = io::write_ply(in.at("prepared").get<std::string>(), *cloud); !ok) {
            return {{"store_error", "cannot write the prepared scan: " + ok.error().message}};
        }
    }
    return {{"summary", campaign_json::summary(summary)}};
}

json describe(const json& in, const CampaignConfig& config, std::vector<unsigned char>& blob) {
    auto cloud = read_cloud(in.at("prepared").get<std::string>());
    if (!cloud) return store_error(cloud.error());
    const ScanDescriptor d =
        describe_campaign_scan(*cloud, in.at("spacing_m").get<double>(), config);
    blob.resize(d.keys.size() * sizeof(std::uint64_t));
    if (!blob.empty()) std::memcpy(blob.data(), d.keys.data(), blob.size());
    return {{"keypoints", d.keypoints}, {"keys", d.keys.size()}, {"problem", d.problem}};
}

json pair(const json& in, const CampaignConfig& config) {
    auto source = read_cloud(in.at("source").get<std::string>());
    if (!source) return store_error(source.error());
    auto target = read_cloud(in.at("target").get<std::string>());
    if (!target) return store_error(target.error());
    return pair_json(register_campaign_pair(*source, *target, config));
}

/// The match graph's doubt and the multi-view stage's warning, either or both.
std::string join_warnings(const std::string& graph, const std::string& multiview) {
    if (graph.empty() || multiview.empty()) return graph + multiview;
    return "match graph: " + graph + "; " + multiview;
}

json stone(const json& in, const CampaignConfig& config) {
    std::vector<ScanInput> inputs;
    std::vector<std::int64_t> ids;
    std::vector<std::string> graph_warnings;
    for (const json& scan : in.at("scans")) {
        const std::string path = scan.at("prepared").get<std::string>();
        ids.push_back(scan.at("id").get<std::int64_t>());
        graph_warnings.push_back(scan.value("graph_warning", std::string()));
        inputs.push_back({.name = path, .load = [path] { return read_cloud(path); }});
    }
    const ScanRegistrationResult r = register_scans(inputs, config.registration, {});
    json scans = json::array();
    for (std::size_t i = 0; i < r.scans.size(); ++i) {
        const ScanOutcome& s = r.scans[i];
        scans.push_back({{"id", ids[i]},
                         {"placed", s.placed},
                         {"pose", campaign_json::pose(s.T_world_scan)},
                         {"reason", s.reason},
                         {"warning", join_warnings(graph_warnings[i], s.warning)}});
    }
    return {{"scans", scans},
            {"placed", r.placed_count},
            {"links", r.link_count},
            {"verified_pairs", r.verified_pair_count},
            {"multiview", std::string(to_string(r.multiview_status))},
            {"reference", ids.empty() ? -1 : ids[r.reference_scan]},
            {"time_s", r.timings.total_s}};
}

json run(const CampaignTask& task, const CampaignConfig& config, std::vector<unsigned char>& blob) {
    const json in = json::parse(task.input_json);
    switch (task.kind) {
        case CampaignTaskKind::kPrepare:
            return prepare(in, config);
        case CampaignTaskKind::kDescribe:
            return describe(in, config, blob);
        case CampaignTaskKind::kPair:
            return pair(in, config);
        case CampaignTaskKind::kStone:
            return stone(in, config);
    }
    return {{"error", "unknown task kind"}};
}

class LocalExecutor : public CampaignExecutor {
public:
    explicit LocalExecutor(const CampaignConfig& config) : config_(config) {}
    Expected<void> run(std::vector<CampaignTask> tasks, const Sink& sink) override {
        std::stable_sort(tasks.begin(), tasks.end(),
                         [](const auto& a, const auto& b) { return a.cost > b.cost; });
        for (const CampaignTask& task : tasks) {
            if (auto ok = sink(run_campaign_task(task, config_)); !ok) return ok;
        }
        return {};
    }
    int ranks() const override { return 1; }

private:
    CampaignConfig config_;
};

}  // namespace

CampaignTaskResult run_campaign_task(const CampaignTask& task, const CampaignConfig& config) {
    CampaignTaskResult result{.kind = task.kind, .id = task.id};
    try {
        result.output_json = run(task, config, result.blob).dump();
    } catch (const std::exception& e) {  // Malformed task JSON or out of memory.
        result.output_json = json{{"error", std::string("task failed: ") + e.what()}}.dump();
    }
    return result;
}

std::unique_ptr<CampaignExecutor> make_local_executor(const CampaignConfig& config) {
    return std::make_unique<LocalExecutor>(config);
}

}  // namespace anascan::acquisition
