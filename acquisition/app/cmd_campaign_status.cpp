// anascan campaign status DIR, campaign export DIR --out OUT/.
#include <spdlog/spdlog.h>

#include <cstdio>
#include <filesystem>
#include <nlohmann/json.hpp>

#include "anascan/acquisition/campaign/campaign_check.hpp"
#include "anascan/acquisition/campaign/campaign_results.hpp"
#include "anascan/processing/io/file_bytes.hpp"
#include "anascan/processing/io/ply.hpp"
#include "anascan/processing/io/stanford_conf.hpp"
#include "campaign_cli.hpp"
#include "commands.hpp"

namespace anascan::cli {
namespace {

namespace fs = std::filesystem;
using acquisition::CampaignStore;
using nlohmann::json;

template <class T>
T must(Expected<T> v) {
    if (!v) fail_command(v.error());
    return std::move(*v);
}

void run_status(const std::string& dir) {
    auto store = CampaignStore::open(dir, true);
    if (!store) fail_command(store.error());
    print_status(**store);
}

struct ExportOptions {
    std::string dir, out;
};

/// Writes OUT/stone_K/{poses.conf, merged.ply, report.json} for one multi-view result.
void export_stone(const CampaignStore& store,
                  const std::vector<acquisition::CampaignScanRow>& scans,
                  const acquisition::CampaignStoneRow& stone, const fs::path& folder) {
    const auto result = must(acquisition::read_stone_result(stone.result_json, scans.size()));
    io::StanfordConf conf;
    PointCloud merged;
    for (const acquisition::CampaignStoneScan& scan : result.scans) {
        if (!scan.placed) continue;
        conf.entries.push_back({scans[static_cast<std::size_t>(scan.id)].file, scan.T_stone_scan});
        auto cloud = io::read_ply(store.prepared_file(scan.id));
        if (!cloud) fail_command(cloud.error());
        append(merged, transformed(cloud->cloud, scan.T_stone_scan));
    }
    std::error_code ec;
    fs::create_directories(folder, ec);
    if (ec) throw CommandFailed(folder.string() + ": cannot create: " + ec.message());
    if (auto ok = io::write_conf(folder / "poses.conf", conf); !ok) fail_command(ok.error());
    if (auto ok = io::write_ply(folder / "merged.ply", merged); !ok) fail_command(ok.error());
    const std::string report = json::parse(stone.result_json).dump(2) + "\n";
    if (auto ok = io::write_file_atomically(folder / "report.json", report); !ok) {
        fail_command(ok.error());
    }
}

void run_export(const ExportOptions& o) {
    auto store = CampaignStore::open(o.dir, true);
    if (!store) fail_command(store.error());
    const auto scans = must((*store)->scans());
    std::size_t written = 0;
    for (const auto& stone : must((*store)->stones())) {
        if (stone.result_json.empty()) continue;
        char name[32];
        std::snprintf(name, sizeof name, "stone_%03lld", static_cast<long long>(stone.id));
        export_stone(**store, scans, stone, fs::path(o.out) / name);
        ++written;
    }
    std::printf("exported %zu stones to %s\n", written, o.out.c_str());
    if (written == 0)
        report_poor_result("no stone has been registered yet: run `anascan campaign register " +
                           o.dir + "`");
}

struct CheckOptions {
    std::string dir;
    bool repair = false, json = false;
};

std::string check_json(const acquisition::CampaignCheckReport& report) {
    json issues = json::array();
    for (const auto& i : report.issues) {
        issues.push_back({{"kind", i.kind},
                          {"id", i.id ? json(*i.id) : json(nullptr)},
                          {"file", i.file.string()},
                          {"problem", i.problem},
                          {"repaired", i.repaired},
                          {"action", i.action}});
    }
    return json{{"campaign", report.dir.string()},
                {"prepared_checked", report.prepared_checked},
                {"prepared_ok", report.prepared_ok},
                {"results_checked", report.results_checked},
                {"integrity", report.integrity},
                {"clean", report.clean()},
                {"issues", issues}}
        .dump(2, ' ', false, json::error_handler_t::replace);
}

void run_check(const CheckOptions& o) {
    auto report = acquisition::check_campaign(o.dir, o.repair);
    if (!report) fail_command(report.error());
    if (o.json) {
        std::printf("%s\n", check_json(*report).c_str());
    } else {
        for (const std::string& line : report->lines()) std::printf("%s\n", line.c_str());
    }
    if (!report->clean()) {
        throw CommandFailed(o.dir + ": " + std::to_string(report->unresolved()) +
                            " problem(s) found" +
                            (o.repair ? " that could not be repaired" : ", not repaired"));
    }
}

void add_check_command(CLI::App& campaign) {
    auto o = std::make_shared<CheckOptions>();
    auto* chk = campaign.add_subcommand(
        "check",
        "Verify the campaign's database, prepared clouds and stored results after a kill or a "
        "disk problem; exit 1 when damage remains. --repair sets damaged work back so that "
        "`campaign register` redoes it, and removes temporary files");
    chk->add_option("dir", o->dir, "Campaign folder")->required();
    chk->add_flag("--repair", o->repair, "Repair what can be repaired (takes the campaign's lock)");
    chk->add_flag("--json", o->json, "Print the report as JSON");
    chk->callback([o] { run_check(*o); });
}

}  // namespace

CampaignConfig stored_config(const CampaignStore& store) {
    CampaignConfig config;
    const auto value = must(store.value("config"));
    if (!value) return config;
    const json j = json::parse(*value, nullptr, false);
    const json* count =
        j.is_object() && j.contains("candidates_per_scan") ? &j["candidates_per_scan"] : nullptr;
    if (count != nullptr && !count->is_number_unsigned()) {
        throw CommandFailed((store.dir() / "campaign.sqlite").string() +
                            ": the stored settings are damaged (candidates_per_scan is not a "
                            "count): start the campaign again with `anascan campaign init`");
    }
    if (count != nullptr) config.candidates_per_scan = count->get<std::size_t>();
    return config;
}

void print_status(const CampaignStore& store) {
    const acquisition::CampaignStatus c = must(acquisition::campaign_status(store));
    std::printf("scans: %zu (prepared %zu, described %zu, not used %zu)\n", c.scans, c.prepared,
                c.described, c.unusable);
    const std::size_t all = c.described * (c.described > 0 ? c.described - 1 : 0) / 2;
    std::printf("candidate pairs: %zu of %zu possible (%.2f %%)\n", c.pairs, all,
                all > 0 ? 100.0 * static_cast<double>(c.pairs) / static_cast<double>(all) : 0.0);
    std::printf("pairs registered: %zu of %zu, verified %zu\n", c.registered, c.pairs, c.verified);
    std::printf("stones: %zu (multi-view done %zu); scans placed %zu of %zu\n", c.stones,
                c.stones_done, c.placed, c.scans);
    for (const std::string& line : c.problems) std::printf("%s\n", line.c_str());
}

void add_campaign_status_commands(CLI::App& campaign) {
    auto dir = std::make_shared<std::string>();
    auto* status =
        campaign.add_subcommand("status", "Stages done, stones, scans not used or not placed");
    status->add_option("dir", *dir, "Campaign folder")->required();
    status->callback([dir] { run_status(*dir); });
    auto opts = std::make_shared<ExportOptions>();
    auto* exp = campaign.add_subcommand(
        "export",
        "Per stone: poses.conf (metres), merged.ply (prepared points, stone frame), report.json");
    exp->add_option("dir", opts->dir, "Campaign folder")->required();
    exp->add_option("--out", opts->out, "Output folder")->required();
    exp->callback([opts] { run_export(*opts); });
    add_check_command(campaign);
}

}  // namespace anascan::cli
