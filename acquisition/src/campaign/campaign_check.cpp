// check_campaign: the store's database, prepared clouds, results and leftover temporaries.
#include "anascan/acquisition/campaign/campaign_check.hpp"

#include <algorithm>
#include <optional>

#include "anascan/acquisition/campaign/campaign_results.hpp"
#include "anascan/acquisition/campaign/campaign_store.hpp"
#include "anascan/processing/io/ply.hpp"

namespace anascan::acquisition {
namespace {

namespace fs = std::filesystem;

/// Why a prepared cloud cannot be used; empty when it reads with the summary's count.
std::string prepared_problem(const fs::path& file, std::size_t expected) {
    std::error_code ec;
    if (!fs::exists(file, ec)) return "prepared cloud missing";
    auto ply = io::read_ply(file);
    if (!ply) return "prepared cloud unreadable: " + ply.error().message;
    if (expected > 0 && ply->cloud.size() != expected) {
        return "prepared cloud holds " + std::to_string(ply->cloud.size()) + " points, " +
               std::to_string(expected) + " were recorded";
    }
    return {};
}

bool known_state(const std::string& state) {
    return state == "new" || state == "prepared" || state == "described" || state == "unusable";
}

/// The scan's stored state and summary; an issue of kind "scan-record" when damaged.
std::optional<CampaignCheckIssue> record_issue(const CampaignScanRow& scan) {
    std::string problem;
    if (!known_state(scan.state)) problem = "unknown state '" + scan.state + "'";
    if (auto summary = read_scan_summary(scan.summary_json); !summary)
        problem = summary.error().message;
    if (problem.empty()) return std::nullopt;
    return CampaignCheckIssue{.kind = "scan-record",
                              .id = scan.id,
                              .problem = "scan " + std::to_string(scan.id) + ": " + problem,
                              .action = "scan set back to new: the next run prepares it again"};
}

/// The prepared cloud of a prepared or described scan; an issue when it cannot be used.
std::optional<CampaignCheckIssue> cloud_issue(const CampaignStore& store,
                                              const CampaignScanRow& scan,
                                              CampaignCheckReport& report) {
    if (scan.state != "prepared" && scan.state != "described") return std::nullopt;
    ++report.prepared_checked;
    const fs::path file = store.prepared_file(scan.id);
    const std::string problem =
        prepared_problem(file, read_scan_summary(scan.summary_json)->points);
    if (problem.empty()) {
        ++report.prepared_ok;
        return std::nullopt;
    }
    return CampaignCheckIssue{.kind = "prepared-cloud",
                              .id = scan.id,
                              .file = file,
                              .problem = problem,
                              .action = "scan set back to new: the next run prepares it again"};
}

Expected<void> check_scans(CampaignStore& store, bool repair, CampaignCheckReport& report) {
    auto scans = store.scans();
    if (!scans) return fail(scans.error());
    for (CampaignScanRow& scan : *scans) {
        auto issue = record_issue(scan);
        if (!issue) issue = cloud_issue(store, scan, report);
        if (!issue) continue;
        if (repair) {
            scan.state = "new";
            scan.problem.clear();
            scan.summary_json.clear();
            if (auto ok = store.save_scan(scan); !ok) return ok;
            issue->repaired = true;
        }
        report.issues.push_back(std::move(*issue));
    }
    return {};
}

Expected<void> check_pairs(CampaignStore& store, bool repair, CampaignCheckReport& report) {
    auto pairs = store.pairs();
    if (!pairs) return fail(pairs.error());
    for (const CampaignPairRow& p : *pairs) {
        if (p.result_json.empty()) continue;
        ++report.results_checked;
        const auto result = read_pair_result(p.result_json);
        if (result) continue;
        CampaignCheckIssue issue{.kind = "pair-result",
                                 .id = p.source,
                                 .problem = "pair " + std::to_string(p.source) + "-" +
                                            std::to_string(p.target) + ": " +
                                            result.error().message,
                                 .action = "result cleared: the next run registers the pair again"};
        if (repair) {
            if (auto ok = store.save_pair_result(p.source, p.target, ""); !ok) return ok;
            issue.repaired = true;
        }
        report.issues.push_back(std::move(issue));
    }
    return {};
}

Expected<void> check_stones(CampaignStore& store, bool repair, CampaignCheckReport& report) {
    auto scans = store.scans();
    if (!scans) return fail(scans.error());
    auto stones = store.stones();
    if (!stones) return fail(stones.error());
    for (const CampaignStoneRow& stone : *stones) {
        if (stone.result_json.empty()) continue;
        ++report.results_checked;
        const auto result = read_stone_result(stone.result_json, scans->size());
        if (result) continue;
        CampaignCheckIssue issue{
            .kind = "stone-result",
            .id = stone.id,
            .problem = "stone " + std::to_string(stone.id) + ": " + result.error().message,
            .action = "result cleared: the next run refines the stone again"};
        if (repair) {
            if (auto ok = store.save_stone_result(stone.id, ""); !ok) return ok;
            issue.repaired = true;
        }
        report.issues.push_back(std::move(issue));
    }
    return {};
}

Expected<void> check_graph(CampaignStore& store, bool repair, CampaignCheckReport& report) {
    auto scans = store.scans();
    if (!scans) return fail(scans.error());
    auto graph = store.value("graph");
    if (!graph) return fail(graph.error());
    const auto warnings = read_graph_warnings(graph->value_or(""), scans->size());
    if (warnings) return {};
    CampaignCheckIssue issue{.kind = "match-graph",
                             .problem = warnings.error().message,
                             .action = "stones cleared: the next run finds them again"};
    if (repair) {
        if (auto ok = store.clear_stones(); !ok) return ok;
        issue.repaired = true;
    }
    report.issues.push_back(std::move(issue));
    return {};
}

void check_temporaries(const fs::path& prepared, bool repair, CampaignCheckReport& report) {
    std::error_code ec;
    for (const auto& entry : fs::directory_iterator(prepared, ec)) {
        const std::string name = entry.path().filename().string();
        if (!name.starts_with('.') || name.find(".tmp") == std::string::npos) continue;
        CampaignCheckIssue issue{.kind = "temporary-file",
                                 .file = entry.path(),
                                 .problem = "left by an interrupted write (never used)",
                                 .action = "removed"};
        std::error_code rm;
        if (repair) issue.repaired = fs::remove(entry.path(), rm);
        report.issues.push_back(std::move(issue));
    }
}

}  // namespace

std::size_t CampaignCheckReport::unresolved() const {
    return static_cast<std::size_t>(std::count_if(issues.begin(), issues.end(), [](const auto& i) {
        return !i.repaired && i.kind != "temporary-file";
    }));
}

std::vector<std::string> CampaignCheckReport::lines() const {
    std::vector<std::string> out;
    for (const CampaignCheckIssue& i : issues) {
        std::string line = i.kind + ": ";
        if (!i.file.empty()) line += i.file.string() + ": ";
        line += i.problem + " (" + (i.repaired ? "repaired: " : "repair: ") + i.action + ")";
        out.push_back(std::move(line));
    }
    out.push_back(dir.string() + ": " + std::to_string(prepared_ok) + " of " +
                  std::to_string(prepared_checked) + " prepared clouds ok, " +
                  std::to_string(results_checked) +
                  " results checked, database integrity: " + integrity +
                  (clean() ? "; clean" : "; " + std::to_string(unresolved()) + " problem(s) left"));
    return out;
}

Expected<CampaignCheckReport> check_campaign(const fs::path& dir, bool repair) {
    auto store = CampaignStore::open(dir, !repair);
    if (!store) return fail(store.error());
    CampaignCheckReport report{.dir = dir};
    auto integrity = (*store)->integrity_check();
    report.integrity = integrity ? *integrity : integrity.error().message;
    if (report.integrity != "ok") {
        report.issues.push_back({.kind = "database",
                                 .file = dir / "campaign.sqlite",
                                 .problem = report.integrity,
                                 .action = "none possible: restore the folder from a copy"});
    }
    for (auto check : {check_scans, check_pairs, check_stones, check_graph}) {
        auto ok = check(**store, repair, report);
        if (ok) continue;
        if (ok.error().code != ErrorCode::kFormat) return fail(ok.error());
        report.issues.push_back({.kind = "database",
                                 .file = dir / "campaign.sqlite",
                                 .problem = ok.error().message,
                                 .action = "none possible: restore the folder from a copy"});
        break;  // The tables contradict each other: the other checks would read them.
    }
    check_temporaries(dir / "prepared", repair, report);
    return report;
}

}  // namespace anascan::acquisition
