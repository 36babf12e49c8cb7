// anascan coverage DIR [--next] [--json] [--out COVERAGE.ply]: how much of the stone the
// session's registered scans cover, where the holes are, and (--next) where to put the
// scanner next.
#include <spdlog/spdlog.h>

#include <cstdio>
#include <nlohmann/json.hpp>

#include "anascan/acquisition/coverage/session_coverage.hpp"
#include "anascan/processing/io/coverage_ply.hpp"
#include "commands.hpp"

namespace anascan::cli {
namespace {

struct CoverageOptions {
    std::string session;
    bool json_output = false;
    bool next = false;
    std::string out;
    double voxel_mm = 2.0;
};

void print_report(const CoverageReport& r) {
    std::printf("coverage %.1f %% of the stone's surface (%.3f m² of %.3f m² observed well)\n",
                r.fraction * 100.0, r.covered_area_m2, r.surface_area_m2);
    std::printf("%zu holes%s\n", r.holes.size(), r.holes.empty() ? "" : " (largest first):");
    for (const CoverageHole& h : r.holes)
        std::printf("  %8.1f cm² at (%.0f, %.0f, %.0f) mm facing (%.2f, %.2f, %.2f)\n",
                    h.area_m2 * 1e4, h.centre_m.x() * 1e3, h.centre_m.y() * 1e3,
                    h.centre_m.z() * 1e3, h.normal.x(), h.normal.y(), h.normal.z());
}

void print_next(const acquisition::SessionNextView& next) {
    std::printf("next: %s\n", next.view.hint.c_str());
    std::printf(
        "(planned from %zu scanner poses in %.2f s; the view keeps %.0f %% overlap with "
        "what is observed; %.0f cm² unobserved that a view from this side can reach, "
        "%.0f cm² only after turning the stone over)\n",
        next.view.candidates, next.plan_s, 100.0 * next.view.overlap_fraction,
        next.view.visible_now_area_m2 * 1e4, next.view.after_turn_area_m2 * 1e4);
}

acquisition::SessionNextView compute(const acquisition::SessionStore& store,
                                     const CoverageOptions& o) {
    const acquisition::SessionCoverageConfig config{.voxel_size_m = o.voxel_mm * 1e-3};
    acquisition::SessionNextView out;
    if (o.next) {
        auto next = acquisition::session_next_view(store, config, {});
        if (!next) fail_command(next.error());
        return std::move(*next);
    }
    auto report =
        acquisition::session_coverage(store, config, [](std::size_t done, std::size_t total) {
            spdlog::info("coverage: scan {}/{} loaded", done, total);
        });
    if (!report) fail_command(report.error());
    out.coverage = std::move(*report);
    return out;
}

void run_coverage(const CoverageOptions& o) {
    auto store =
        acquisition::SessionStore::open(o.session, acquisition::SessionOpenMode::kOpenExisting);
    if (!store) fail_command(store.error());
    const acquisition::SessionNextView result = compute(**store, o);
    const CoverageReport& report = result.coverage;
    const std::string json = coverage_to_json(report);
    if (auto stored = (*store)->set_value("coverage", json); !stored)
        spdlog::warn("coverage not stored in the session: {}", stored.error().message);
    if (!o.out.empty()) {
        if (auto ok = io::write_coverage_ply(o.out, report); !ok) fail_command(ok.error());
        spdlog::info("coverage samples (green observed, red holes) written to {}", o.out);
    }
    if (o.json_output) {
        nlohmann::json j = nlohmann::json::parse(json);
        if (o.next) j["next_view"] = nlohmann::json::parse(next_view_to_json(result.view));
        std::printf("%s\n", j.dump(2).c_str());
        return;
    }
    print_report(report);
    if (o.next) print_next(result);
}

}  // namespace

void add_coverage_command(CLI::App& app) {
    auto opts = std::make_shared<CoverageOptions>();
    auto* cmd = app.add_subcommand(
        "coverage", "Fraction of the stone's surface observed well, and the holes left");
    cmd->add_option("session", opts->session, "Session folder")
        ->required()
        ->check(CLI::ExistingDirectory);
    cmd->add_flag("--json", opts->json_output, "JSON on stdout");
    cmd->add_flag("--next", opts->next,
                  "Also say where to put the scanner next (next-best-view), or when to turn "
                  "the stone over");
    cmd->add_option("--out", opts->out,
                    "Coloured surface samples (.ply): green observed, red holes");
    cmd->add_option("--voxel-mm", opts->voxel_mm,
                    "Scans down-sampled to this voxel first, mm (default 2)")
        ->check(CLI::Range(0.1, 50.0));
    cmd->callback([opts] { run_coverage(*opts); });
}

}  // namespace anascan::cli
