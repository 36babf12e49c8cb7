// run_campaign: the stages as task lists, each result recorded as it arrives.
#include "anascan/acquisition/campaign/campaign_job.hpp"

#include <cmath>
#include <cstring>
#include <filesystem>
#include <limits>
#include <map>
#include <optional>

#include "anascan/processing/core/stopwatch.hpp"
#include "campaign/campaign_json.hpp"
#include "campaign/job_steps.hpp"

namespace anascan::acquisition {

using nlohmann::json;

namespace campaign_steps {

/// A task that failed on the campaign's own files (disk full, a damaged prepared cloud)
/// stops the job and records nothing: the scan or pair is not at fault, and a rerun redoes
/// it once the cause is fixed. Failures of a user's scan file are results, recorded.
std::optional<std::string> store_problem(const CampaignTaskResult& result) {
    const json out = json::parse(result.output_json, nullptr, false);
    if (!out.is_object() || !out.contains("store_error")) return std::nullopt;
    return out["store_error"].get<std::string>();
}

Expected<void> run_stage(StageRun& run, const std::string& name, std::vector<CampaignTask> tasks,
                         std::size_t done_before, const CampaignExecutor::Sink& sink) {
    run.report.stages.push_back({name, done_before, tasks.size()});
    CampaignProgress p{.stage = name,
                       .done = done_before,
                       .total = done_before + tasks.size(),
                       .done_before = done_before};
    if (run.progress) run.progress(p);
    if (tasks.empty()) return {};
    const Stopwatch watch;
    return run.executor.run(std::move(tasks), [&](CampaignTaskResult result) -> Expected<void> {
        if (auto problem = store_problem(result)) return fail(ErrorCode::kIo, *problem);
        if (auto ok = sink(std::move(result)); !ok) return ok;
        ++p.done;
        const double seconds = std::max(watch.seconds(), 1e-9);
        p.rate_per_s = static_cast<double>(p.done - done_before) / seconds;
        p.eta_s = static_cast<double>(p.total - p.done) / std::max(p.rate_per_s, 1e-12);
        if (run.progress) run.progress(p);
        return {};
    });
}

PreparedSummary summary_of(const CampaignScanRow& row) {
    if (row.summary_json.empty()) return {};
    return campaign_json::summary_from(json::parse(row.summary_json));
}

}  // namespace campaign_steps

using namespace campaign_steps;

namespace {

std::size_t file_bytes(const std::string& path) {
    std::error_code ec;
    const auto size = std::filesystem::file_size(path, ec);
    return ec ? 0 : static_cast<std::size_t>(size);
}

Expected<void> prepare_stage(StageRun& run, CampaignStore& store,
                             std::vector<CampaignScanRow>& scans) {
    std::vector<CampaignTask> tasks;
    for (const CampaignScanRow& s : scans) {
        if (s.state != "new") continue;
        const json in = {{"file", s.file}, {"prepared", store.prepared_file(s.id).string()}};
        tasks.push_back(
            {CampaignTaskKind::kPrepare, s.id, in.dump(), static_cast<double>(file_bytes(s.file))});
    }
    const std::size_t done = scans.size() - tasks.size();
    return run_stage(run, "prepare", std::move(tasks), done,
                     [&](CampaignTaskResult r) -> Expected<void> {
                         CampaignScanRow& row = scans[static_cast<std::size_t>(r.id)];
                         const json out = json::parse(r.output_json);
                         if (out.contains("error")) {
                             row.state = "unusable";
                             row.problem = out["error"].get<std::string>();
                         } else {
                             const PreparedSummary s = campaign_json::summary_from(out["summary"]);
                             row.summary_json = out["summary"].dump();
                             row.state = s.problem.empty() ? "prepared" : "unusable";
                             row.problem = s.problem;
                         }
                         return store.save_scan(row);
                     });
}

/// A prepared scan with the same points as an earlier one is not used (a copied file).
Expected<void> mark_duplicates(CampaignStore& store, std::vector<CampaignScanRow>& scans) {
    std::map<std::uint64_t, std::size_t> first;
    std::vector<CampaignScanRow> changed;
    for (std::size_t i = 0; i < scans.size(); ++i) {
        if (scans[i].state == "unusable" || scans[i].summary_json.empty()) continue;
        const std::uint64_t hash = summary_of(scans[i]).position_hash;
        const auto [it, inserted] = first.emplace(hash, i);
        if (inserted) continue;
        scans[i].state = "unusable";
        scans[i].problem = "the same points as " + scans[it->second].file + " (a duplicate file)";
        changed.push_back(scans[i]);
    }
    return changed.empty() ? Expected<void>{} : store.save_scans(changed);
}

Expected<void> describe_stage(StageRun& run, CampaignStore& store,
                              std::vector<CampaignScanRow>& scans) {
    std::vector<CampaignTask> tasks;
    std::size_t done = 0;
    for (const CampaignScanRow& s : scans) {
        done += s.state == "described";
        if (s.state != "prepared") continue;
        const PreparedSummary summary = summary_of(s);
        const json in = {{"prepared", store.prepared_file(s.id).string()},
                         {"spacing_m", summary.spacing_m}};
        tasks.push_back(
            {CampaignTaskKind::kDescribe, s.id, in.dump(), static_cast<double>(summary.points)});
    }
    return run_stage(
        run, "describe", std::move(tasks), done, [&](CampaignTaskResult r) -> Expected<void> {
            CampaignScanRow& row = scans[static_cast<std::size_t>(r.id)];
            const json out = json::parse(r.output_json);
            const std::string problem = out.contains("error") ? out["error"].get<std::string>()
                                                              : out.value("problem", std::string());
            row.state = problem.empty() ? "described" : "unusable";
            row.problem = problem;
            row.keys.resize(r.blob.size() / sizeof(std::uint64_t));
            if (!row.keys.empty())
                std::memcpy(row.keys.data(), r.blob.data(),
                            row.keys.size() * sizeof(std::uint64_t));
            return store.save_scan(row);
        });
}

Expected<void> candidate_stage(StageRun& run, CampaignStore& store,
                               const std::vector<CampaignScanRow>& scans,
                               const CampaignConfig& config) {
    auto done = store.value("candidates");
    if (!done) return fail(done.error());
    run.report.stages.push_back({"candidates", *done ? 1u : 0u, *done ? 0u : 1u});
    if (*done) return {};
    std::vector<std::vector<std::uint64_t>> keys;
    std::vector<std::int64_t> ids;
    for (const CampaignScanRow& s : scans) {
        if (s.state != "described") continue;
        keys.push_back(s.keys);
        ids.push_back(s.id);
    }
    const Stopwatch watch;
    std::vector<CampaignPairRow> rows;
    for (const CandidatePair& c : propose_candidates(keys, config)) {
        rows.push_back(
            {.source = ids[c.source], .target = ids[c.target], .similarity = c.similarity});
    }
    if (auto ok = store.set_candidates(rows); !ok) return ok;
    const std::size_t n = ids.size();
    const json figures = {{"scans", n},
                          {"pairs", rows.size()},
                          {"all_pairs", n * (n > 0 ? n - 1 : 0) / 2},
                          {"time_s", watch.seconds()}};
    if (run.progress) run.progress({.stage = "candidates", .done = 1, .total = 1});
    return store.set_value("candidates", figures.dump());
}

Expected<void> pair_stage(StageRun& run, CampaignStore& store,
                          const std::vector<CampaignScanRow>& scans) {
    auto pairs = store.pairs();
    if (!pairs) return fail(pairs.error());
    std::vector<CampaignTask> tasks;
    std::map<std::int64_t, std::pair<std::int64_t, std::int64_t>> pair_of_task;
    for (const CampaignPairRow& p : *pairs) {
        if (!p.result_json.empty()) continue;
        const auto s = static_cast<std::size_t>(p.source), t = static_cast<std::size_t>(p.target);
        const json in = {{"source", store.prepared_file(p.source).string()},
                         {"target", store.prepared_file(p.target).string()}};
        const auto id = static_cast<std::int64_t>(pair_of_task.size());
        pair_of_task[id] = {p.source, p.target};
        tasks.push_back({CampaignTaskKind::kPair, id, in.dump(),
                         static_cast<double>(summary_of(scans[s]).points) *
                             static_cast<double>(summary_of(scans[t]).points)});
    }
    const std::size_t done = pairs->size() - tasks.size();
    return run_stage(run, "pairs", std::move(tasks), done,
                     [&](CampaignTaskResult r) -> Expected<void> {
                         const auto [source, target] = pair_of_task.at(r.id);
                         return store.save_pair_result(source, target, r.output_json);
                     });
}

}  // namespace

Expected<CampaignJobReport> run_campaign(CampaignStore& store, CampaignExecutor& executor,
                                         const CampaignConfig& config, const Progress& progress) {
    CampaignJobReport report;
    StageRun run{executor, progress, report};
    auto scans = store.scans();
    if (!scans) return fail(scans.error());
    if (auto ok = campaign_json::verify_stored(store, *scans); !ok) return fail(ok.error());
    if (auto ok = prepare_stage(run, store, *scans); !ok) return fail(ok.error());
    if (auto ok = mark_duplicates(store, *scans); !ok) return fail(ok.error());
    if (auto ok = describe_stage(run, store, *scans); !ok) return fail(ok.error());
    if (auto ok = candidate_stage(run, store, *scans, config); !ok) return fail(ok.error());
    if (auto ok = pair_stage(run, store, *scans); !ok) return fail(ok.error());
    if (auto ok = stone_stages(run, store, *scans, config); !ok) return fail(ok.error());
    return report;
}

}  // namespace anascan::acquisition
