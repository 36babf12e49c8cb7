// anascan assemble POSES.conf: place scans with known poses, check agreement, merge.
#include <cstdio>

#include "anascan/acquisition/assembly/assembly.hpp"
#include "anascan/processing/io/file_bytes.hpp"
#include "anascan/processing/io/ply.hpp"
#include "assemble_runner.hpp"
#include "commands.hpp"
#include "point_files.hpp"

namespace anascan::cli {

void print_assembly(const acquisition::AssemblyReport& report) {
    std::printf("distances from each point to the nearest surface of the other scan%s\n",
                report.pairs.empty() || report.pairs[0].agreement.point_to_plane
                    ? " (along its normal)"
                    : "");
    std::printf("%-14s %-14s %9s %11s %11s\n", "scan A", "scan B", "overlap", "median mm",
                "rms mm");
    for (const acquisition::PairReport& p : report.pairs) {
        std::printf("%-14s %-14s %8.1f%% %11.3f %11.3f\n", p.a.c_str(), p.b.c_str(),
                    100.0 * p.agreement.overlap_fraction, 1e3 * p.agreement.median_distance_m,
                    1e3 * p.agreement.rms_distance_m);
    }
    std::printf("%zu scans, %zu overlapping pairs: median of pair medians %.3f mm, worst %.3f mm\n",
                report.scans.size(), report.pairs.size(), 1e3 * report.median_pair_distance_m,
                1e3 * report.worst_pair_distance_m);
}

acquisition::AssemblyReport run_assemble(const AssembleOptions& o) {
    if (!o.model_out.empty()) check_point_output(o.model_out);
    check_output_writable(o.model_out, "--out");
    check_output_writable(o.report_out, "--report");
    acquisition::AssemblyConfig config{.model_voxel_m = o.voxel_mm * 1e-3,
                                       .min_pair_overlap = o.min_overlap_percent / 100.0};
    config.agreement.overlap_radius_m = o.overlap_radius_mm * 1e-3;
    auto report = acquisition::assemble_from_conf(
        o.conf, config, [](std::string_view m) { spdlog::info("{}", m); });
    if (!report) fail_command(report.error());
    print_assembly(*report);
    if (!o.model_out.empty()) {
        write_points(o.model_out, report->model);
        std::printf("model: %s (%zu points)\n", o.model_out.c_str(), report->model.size());
    }
    if (!o.report_out.empty()) {
        const std::string json = acquisition::report_to_json(*report);
        if (auto ok = io::write_file_atomically(o.report_out, json); !ok) fail_command(ok.error());
        std::printf("report: %s\n", o.report_out.c_str());
    }
    return std::move(*report);
}

void add_assemble_command(CLI::App& app) {
    auto opts = std::make_shared<AssembleOptions>();
    auto* cmd =
        app.add_subcommand("assemble",
                           "Place scans with the poses of a Stanford .conf, measure how well "
                           "overlapping scans agree, and write the merged model");
    cmd->add_option("conf", opts->conf, "Pose file (bmesh FILE tx ty tz qx qy qz qw)")
        ->required()
        ->check(CLI::ExistingFile);
    cmd->add_option("--out", opts->model_out,
                    "Merged model (.ply, or .xyz/.txt/.asc for XYZ text)");
    cmd->add_option("--report", opts->report_out, "Agreement report (.json)");
    cmd->add_option("--voxel-mm", opts->voxel_mm, "Down-sample the model to this voxel size, mm")
        ->check(CLI::NonNegativeNumber);
    cmd->add_option("--overlap-radius-mm", opts->overlap_radius_mm,
                    "A point overlaps another scan when it has a neighbour this close, mm")
        ->check(CLI::PositiveNumber);
    cmd->add_option("--min-overlap", opts->min_overlap_percent,
                    "Report pairs overlapping at least this much, percent (default 10)")
        ->check(CLI::Range(0.0, 100.0));
    cmd->callback([opts] { run_assemble(*opts); });
}

}  // namespace anascan::cli
