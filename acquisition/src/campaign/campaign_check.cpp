// check_campaign: the store's database, prepared clouds, results and leftover temporaries.
#include "anascan/acquisition/campaign/campaign_check.hpp"

#include <algorithm>
#include <nlohmann/json.hpp>

#include "anascan/acquisition/campaign/campaign_store.hpp"
#include "anascan/processing/io/ply.hpp"
#include "campaign/campaign_json.hpp"

namespace anascan::acquisition {
namespace {

namespace fs = std::filesystem;
using nlohmann::json;

bool object_json(const std::string& text) {
    const json j = json::parse(text, nullptr, false);
    return j.is_object();
}

/// Why a prepared cloud cannot be used; empty when it reads with the summary's count.
std::string prepared_problem(const fs::path& file, const CampaignScanRow& scan) {
    std::error_code ec;
    if (!fs::exists(file, ec)) return "prepared cloud missing";
    auto ply = io::read_ply(file);
    if (!ply) return "prepared cloud unreadable: " + ply.error().message;
    const std::size_t expected =
        scan.summary_json.empty()
            ? 0
            : campaign_json::summary_from(json::parse(scan.summary_json, nullptr, false)).points;
    if (expected > 0 && ply->cloud.size() != expected) {
        return "prepared cloud holds " + std::to_string(ply->cloud.size()) + " points, " +
               std::to_string(expected) + " were recorded";
    }
    return {};
}

Expected<void> check_prepared(CampaignStore& store, bool repair, CampaignCheckReport& report) {
    auto scans = store.scans();
    if (!scans) return fail(scans.error());
    for (CampaignScanRow& scan : *scans) {
        if (scan.state != "prepared" && scan.state != "described") continue;
        ++report.prepared_checked;
        const fs::path file = store.prepared_file(scan.id);
        const std::string problem = prepared_problem(file, scan);
        if (problem.empty()) {
            ++report.prepared_ok;
            continue;
        }
        CampaignCheckIssue issue{.kind = "prepared-cloud",
                                 .id = scan.id,
                                 .file = file,
                                 .problem = problem,
                                 .action = "scan set back to new: the next run prepares it again"};
        if (repair) {
            scan.state = "new";
            if (auto ok = store.save_scan(scan); !ok) return ok;
            issue.repaired = true;
        }
        report.issues.push_back(std::move(issue));
    }
    return {};
}

Expected<void> check_pairs(CampaignStore& store, bool repair, CampaignCheckReport& report) {
    auto pairs = store.pairs();
    if (!pairs) return fail(pairs.error());
    for (const CampaignPairRow& p : *pairs) {
        if (p.result_json.empty()) continue;
        ++report.results_checked;
        if (object_json(p.result_json)) continue;
        CampaignCheckIssue issue{.kind = "pair-result",
                                 .id = p.source,
                                 .problem = "pair " + std::to_string(p.source) + "-" +
                                            std::to_string(p.target) +
                                            ": stored result is not valid JSON",
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
    auto stones = store.stones();
    if (!stones) return fail(stones.error());
    for (const CampaignStoneRow& stone : *stones) {
        if (stone.result_json.empty()) continue;
        ++report.results_checked;
        if (object_json(stone.result_json)) continue;
        CampaignCheckIssue issue{
            .kind = "stone-result",
            .id = stone.id,
            .problem = "stone " + std::to_string(stone.id) + ": stored result is not valid JSON",
            .action = "result cleared: the next run refines the stone again"};
        if (repair) {
            if (auto ok = store.save_stone_result(stone.id, ""); !ok) return ok;
            issue.repaired = true;
        }
        report.issues.push_back(std::move(issue));
    }
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
    if (auto ok = check_prepared(**store, repair, report); !ok) return fail(ok.error());
    if (auto ok = check_pairs(**store, repair, report); !ok) return fail(ok.error());
    if (auto ok = check_stones(**store, repair, report); !ok) return fail(ok.error());
    check_temporaries(dir / "prepared", repair, report);
    return report;
}

}  // namespace anascan::acquisition
