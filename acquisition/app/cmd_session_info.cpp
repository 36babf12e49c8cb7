// anascan session info DIR / session check DIR: what a session holds; is it intact.
#include <cstdio>
#include <nlohmann/json.hpp>

#include "anascan/acquisition/store/session_check.hpp"
#include "anascan/acquisition/store/session_json.hpp"
#include "commands.hpp"
#include "session_cli.hpp"

namespace anascan::cli {
namespace {

using acquisition::ScanRecord;
using acquisition::ScanState;

struct InfoOptions {
    std::string dir;
    bool json = false;
    bool repair = false;
};

template <class T>
T value_or_fail(Expected<T> result) {
    if (!result) fail_command(result.error());
    return std::move(*result);
}

void print_summary(const acquisition::SessionStore& store, const std::vector<ScanRecord>& scans) {
    std::size_t counts[5] = {0, 0, 0, 0, 0};
    for (const ScanRecord& r : scans) ++counts[static_cast<int>(r.state)];
    const auto coverage = value_or_fail(acquisition::coverage_fraction(store));
    std::printf(
        "session %s: %zu scans (%zu registered, %zu flagged, %zu failed, %zu queued, %zu "
        "excluded)",
        store.dir().c_str(), scans.size(), counts[1], counts[4], counts[2], counts[0], counts[3]);
    if (coverage) std::printf(", coverage %.1f %%", 100.0 * *coverage);
    std::printf("\n");
    for (const auto& d : value_or_fail(store.devices())) {
        std::printf("device: %s (%s)\n", d.id.c_str(), to_string(d.kind));
    }
}

void print_scans(const std::vector<ScanRecord>& scans) {
    std::printf("%5s %-22s %-10s %5s %9s %10s %12s  %s\n", "seq", "file", "state", "group",
                "points", "latency s", "shift m", "captured (UTC)");
    for (const ScanRecord& r : scans) {
        char latency[32] = "-";
        if (r.latency_s) std::snprintf(latency, sizeof(latency), "%.3f", *r.latency_s);
        char shift[32] = "-";
        if (r.pose) std::snprintf(shift, sizeof(shift), "%.4f", r.pose->translation().norm());
        std::printf("%5lld %-22s %-10s %5d %9zu %10s %12s  %s%s%s\n", static_cast<long long>(r.seq),
                    r.file.c_str(), std::string(to_string(r.state)).c_str(), r.group, r.point_count,
                    latency, shift, acquisition::format_utc(r.captured_at).c_str(),
                    r.turned_over_before ? "  (after turning over)" : "",
                    r.file_problem.empty() ? "" : ("  FILE: " + r.file_problem).c_str());
    }
}

void run_info(const InfoOptions& o) {
    auto store = open_session(o.dir, acquisition::SessionOpenMode::kReadOnly);
    if (o.json) {
        std::printf("%s\n", value_or_fail(acquisition::session_info_json(*store)).c_str());
        return;
    }
    const auto scans = value_or_fail(store->scans());
    print_summary(*store, scans);
    print_scans(scans);
    std::printf("events: %zu\n", value_or_fail(store->events()).size());
    for (const auto& n : value_or_fail(store->notes())) {
        std::printf("note%s: %s\n", n.seq ? (" (scan " + std::to_string(*n.seq) + ")").c_str() : "",
                    n.text.c_str());
    }
}

std::string report_json(const acquisition::SessionCheckReport& report) {
    nlohmann::json issues = nlohmann::json::array();
    for (const auto& i : report.issues) {
        issues.push_back({{"kind", std::string(to_string(i.kind))},
                          {"seq", i.seq ? nlohmann::json(*i.seq) : nlohmann::json(nullptr)},
                          {"file", i.file.string()},
                          {"problem", i.problem},
                          {"repaired", i.repaired},
                          {"recorded", i.recorded},
                          {"action", i.action}});
    }
    return nlohmann::json{{"session", report.dir.string()}, {"scans_checked", report.scans_checked},
                          {"scans_ok", report.scans_ok},    {"integrity", report.integrity},
                          {"clean", report.clean()},        {"issues", issues}}
        .dump(2, ' ', false, nlohmann::json::error_handler_t::replace);  // file names from rows
}

void run_check(const InfoOptions& o) {
    const auto report = value_or_fail(acquisition::check_session(o.dir, {.repair = o.repair}));
    if (o.json) {
        std::printf("%s\n", report_json(report).c_str());
    } else {
        for (const std::string& line : report.lines()) std::printf("%s\n", line.c_str());
    }
    if (!report.clean()) {
        throw CommandFailed(o.dir + ": " + std::to_string(report.unresolved()) +
                            " problem(s) found" +
                            (o.repair ? " that could not be repaired" : ", not repaired"));
    }
}

}  // namespace

void add_session_info_commands(CLI::App& session) {
    auto info = std::make_shared<InfoOptions>();
    auto* cmd = session.add_subcommand(
        "info", "The scans of a session (state, group, latency), its devices, events and notes");
    cmd->add_option("dir", info->dir, "Session folder")->required();
    cmd->add_flag("--json", info->json,
                  "JSON: scans with seq, file, state, group, pose and true_pose (16 numbers, "
                  "row-major T_world_scan, metres) or null, latency_s; coverage fraction");
    cmd->callback([info] { run_info(*info); });

    auto check = std::make_shared<InfoOptions>();
    auto* chk = session.add_subcommand(
        "check",
        "Verify every scan file against the database and find what a crash left; exit 1 when "
        "problems remain. --repair removes temporary files, moves unacknowledged scan files to "
        "DIR/recovered/ and marks scans with damaged files failed (never deletes a scan)");
    chk->add_option("dir", check->dir, "Session folder")->required();
    chk->add_flag("--repair", check->repair, "Repair what can be repaired");
    chk->add_flag("--json", check->json, "Print the report as JSON");
    chk->callback([check] { run_check(*check); });
}

}  // namespace anascan::cli
