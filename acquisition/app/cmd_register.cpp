// anascan register SCAN.ply... --out POSES.conf: register unordered scans without poses.
#include <spdlog/spdlog.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <nlohmann/json.hpp>

#include "anascan/processing/core/allocator.hpp"
#include "anascan/processing/io/file_bytes.hpp"
#include "anascan/processing/io/ply.hpp"
#include "anascan/processing/io/stanford_conf.hpp"
#include "anascan/processing/registration/batch/scan_registration.hpp"
#include "commands.hpp"
#include "point_files.hpp"
#include "register_consistency.hpp"
#include "scan_preparation.hpp"
#include "scan_region.hpp"

namespace anascan::cli {
namespace {

namespace fs = std::filesystem;

struct RegisterOptions {
    std::vector<std::string> scans;
    std::string out;
    std::string merged;
    std::string stats;
    SensorOptions sensor;
    RegionOptions region;
};

/// The scan's name in the .conf: relative to the .conf's folder when possible.
std::string conf_name(const std::string& scan, const std::string& conf) {
    std::error_code ec;
    const fs::path scan_abs = fs::absolute(scan, ec);
    const fs::path folder = fs::absolute(conf, ec).parent_path();
    if (ec) return scan;
    const fs::path relative = scan_abs.lexically_normal().lexically_relative(folder);
    return relative.empty() ? scan : relative.generic_string();
}

std::size_t refined_pair_count(const ScanRegistrationResult& r) {
    return static_cast<std::size_t>(std::count_if(r.pairs.begin(), r.pairs.end(),
                                                  [](const auto& p) { return p.global.refined; }));
}

void print_result(const ScanRegistrationResult& r) {
    std::printf("%-28s %-10s %6s %10s\n", "scan", "status", "group", "points");
    for (const ScanOutcome& s : r.scans) {
        std::printf("%-28s %-10s %6d %10zu\n", s.name.c_str(), s.placed ? "placed" : "NOT placed",
                    s.group, s.point_count);
    }
    for (const ScanOutcome& s : r.scans) {
        if (!s.placed) std::printf("not placed: %s: %s\n", s.name.c_str(), s.reason.c_str());
        if (!s.warning.empty()) spdlog::warn("{}: {}", s.name, s.warning);
    }
    const ScanRegistrationTimings& t = r.timings;
    std::printf(
        "placed %zu of %zu scans (%zu groups); %zu of %zu pairs verified (%zu refined), %zu links, "
        "%zu dropped; multi-view %s\n",
        r.placed_count, r.scans.size(), r.group_count, r.verified_pair_count, r.pairs.size(),
        refined_pair_count(r), r.link_count, r.dropped_link_count,
        std::string(to_string(r.multiview_status)).c_str());
    if (std::isfinite(r.session_rms_gate_m)) {
        std::printf("session RMS gate %.3f mm: %zu verified pairs above it not used\n",
                    r.session_rms_gate_m * 1e3, r.gated_pair_count);
    }
    std::printf(
        "time: prepare %.2f s, features %.2f s, matching %.2f s, pairwise %.2f s, pose graph "
        "%.3f s, fine %.2f s, multi-view %.2f s, total %.2f s\n",
        t.prepare_s, t.features_s, t.matching_s, t.pairwise_s, t.pose_graph_s, t.fine_s,
        t.multiview_s, t.total_s);
}

nlohmann::json fine_summary(const ScanRegistrationResult& r) {
    int iterations = 0, count = 0;
    double time_s = 0.0, rms_sq = 0.0, overlap = 0.0;
    for (const PairOutcome& p : r.pairs) {
        if (p.fine.status == FineRegistrationStatus::kInvalidInput) continue;  // Not tried.
        iterations += p.fine.iterations;
        time_s += p.fine.time_s;
        rms_sq += p.fine.rms_m * p.fine.rms_m;
        overlap += p.fine.overlap_fraction;
        ++count;
    }
    const double n = std::max(count, 1);
    return {{"pairs", count},
            {"iterations", iterations},
            {"time_s", time_s},
            {"rms_m", std::sqrt(rms_sq / n)},
            {"overlap", overlap / n}};
}

/// 4x4 row-major.
nlohmann::json matrix_json(const Pose& T) {
    nlohmann::json rows = nlohmann::json::array();
    for (int i = 0; i < 4; ++i)
        for (int j = 0; j < 4; ++j) rows.push_back(T.matrix()(i, j));
    return rows;
}

nlohmann::json pair_json(const ScanRegistrationResult& r, const PairOutcome& p) {
    return {{"source", r.scans[p.source].name},
            {"target", r.scans[p.target].name},
            {"match_score", p.match_score},
            {"hypotheses", p.hypotheses},
            {"global_skipped", p.global.skipped},
            {"global_status", p.global.skipped ? std::string("skipped (already connected)")
                                               : std::string(to_string(p.global.status))},
            {"global_refined", p.global.refined},
            {"verified", p.verified},
            {"above_rms_gate", p.above_rms_gate},
            {"free_space_rejections", p.free_space_rejections},
            {"slide_probes", p.slides.probes},
            {"slide_ambiguous", p.slides.ambiguous},
            {"slide_m", p.slides.slide_m},
            {"in_tree", p.in_tree},
            {"weight", p.weight},
            {"T_target_source", matrix_json(p.T_target_source)},
            {"global_rms_m", p.global.rms_m},
            {"global_overlap", p.global.overlap_fraction},
            {"global_time_s", p.global.time_s},
            {"fine_status", std::string(to_string(p.fine.status))},
            {"fine_iterations", p.fine.iterations},
            {"fine_rms_m", p.fine.rms_m},
            {"fine_overlap", p.fine.overlap_fraction},
            {"fine_eigenvalue_ratio", p.fine.eigenvalue_ratio},
            {"fine_time_s", p.fine.time_s},
            {"linked", p.linked},
            {"link_dropped", p.link_dropped}};
}

std::string stats_json(const ScanRegistrationResult& r) {
    const ScanRegistrationTimings& t = r.timings;
    nlohmann::json pairs = nlohmann::json::array(), scans = nlohmann::json::array();
    for (const PairOutcome& p : r.pairs) pairs.push_back(pair_json(r, p));
    for (const ScanOutcome& s : r.scans) {
        scans.push_back({{"name", s.name},
                         {"placed", s.placed},
                         {"reason", s.reason},
                         {"warning", s.warning},
                         {"group", s.group},
                         {"points", s.point_count},
                         {"spacing_m", s.spacing_m},
                         {"normals_estimated", s.normals_estimated}});
    }
    const nlohmann::json doc = {{"stages",
                                 {{"prepare", t.prepare_s},
                                  {"features", t.features_s},
                                  {"matching", t.matching_s},
                                  {"pairwise", t.pairwise_s},
                                  {"pose_graph", t.pose_graph_s},
                                  {"fine", t.fine_s},
                                  {"multiview", t.multiview_s},
                                  {"total", t.total_s}}},
                                {"fine", fine_summary(r)},
                                {"multiview_status", std::string(to_string(r.multiview_status))},
                                {"session_rms_gate_m", std::isfinite(r.session_rms_gate_m)
                                                           ? nlohmann::json(r.session_rms_gate_m)
                                                           : nlohmann::json(nullptr)},
                                {"pairs", pairs},
                                {"scans", scans}};
    return doc.dump(2) + "\n";
}

/// Appends every placed scan, re-read and moved into the world frame, one at a time.
void write_merged(const RegisterOptions& o, const ScanRegistrationResult& r) {
    PointCloud merged;
    for (std::size_t i = 0; i < r.scans.size(); ++i) {
        if (!r.scans[i].placed) continue;
        auto cloud = load_ply_cloud(o.scans[i]);
        if (!cloud) fail_command(cloud.error());
        cloud->normals.clear();  // Some scans may lack them; append keeps common ones only.
        append(merged, transformed(*cloud, r.scans[i].T_world_scan));
    }
    write_points(o.merged, merged);
    std::printf("merged: %s (%zu points)\n", o.merged.c_str(), merged.size());
}

void write_outputs(const RegisterOptions& o, const ScanRegistrationResult& r) {
    io::StanfordConf conf;
    for (std::size_t i = 0; i < r.scans.size(); ++i) {
        if (r.scans[i].placed)
            conf.entries.push_back({conf_name(o.scans[i], o.out), r.scans[i].T_world_scan});
    }
    if (auto ok = io::write_conf(o.out, conf); !ok) fail_command(ok.error());
    std::printf("poses: %s (%zu scans)\n", o.out.c_str(), conf.entries.size());
    if (!o.stats.empty()) {
        if (auto ok = io::write_file_atomically(o.stats, stats_json(r)); !ok) {
            fail_command(ok.error());
        }
        std::printf("stats: %s\n", o.stats.c_str());
    }
    if (!o.merged.empty()) write_merged(o, r);
}

/// The placed scans checked against each other when their sensor position is known (the
/// free-space test needs it; the normal and relief tests alone, calibrated on one scan's own
/// noise, flagged true bunny pairs); those taken out are reported.
RegisterConsistency check_consistency(const std::vector<ScanInput>& inputs,
                                      ScanRegistrationResult& result) {
    if (inputs.empty() || !inputs[0].sensor_origin_known) {
        std::printf(
            "consistency: not checked (give --sensor-origin to check the placed scans "
            "against each other)\n");
        return {};
    }
    const RegisterConsistency c = check_placed_scans(
        result, [&](std::size_t i) { return inputs[i].load(); }, inputs[0].sensor_origin_scan_m);
    std::printf(
        "consistency: %zu placed scans checked pairwise (%zu overlapping pairs), %zu taken out\n",
        c.checked, c.pairs, c.taken_out);
    for (const ScanOutcome& s : result.scans)
        if (!s.placed && s.reason.starts_with("contradicts"))
            spdlog::warn("{} taken out: {}", s.name, s.reason);
    return c;
}

void run_register(const RegisterOptions& o) {
    check_output_writable(o.out, "--out");
    check_output_writable(o.stats, "--stats");
    if (!o.merged.empty()) check_point_output(o.merged);
    check_output_writable(o.merged, "--merged");
    // Large per-scan buffers mapped and returned on free: peak memory does not grow with
    // the number of scans through heap fragmentation (docs/scan-registration.md, "Scale").
    if (!use_fixed_mmap_threshold()) spdlog::debug("allocator: mmap threshold not fixed");
    std::vector<ScanInput> inputs;
    for (const std::string& path : o.scans) {
        inputs.push_back({.name = path,
                          .load = [path, &o]() -> Expected<PointCloud> {
                              auto cloud = load_ply_cloud(path);
                              if (!cloud) return cloud;
                              try {  // Loads may run on worker threads: no exception out.
                                  return select_region(*cloud, o.region, path);
                              } catch (const CommandFailed& e) {
                                  return fail(ErrorCode::kEmpty, e.what());
                              }
                          },
                          .sensor_origin_scan_m = sensor_origin(o.sensor),
                          .sensor_origin_known = o.sensor.origin_given && !o.sensor.no_sensor});
    }
    ScanRegistrationResult result =
        register_scans(inputs, {}, [](std::string_view m) { spdlog::info("{}", m); });
    const RegisterConsistency consistency = check_consistency(inputs, result);
    print_result(result);
    if (result.placed_count == 0) throw CommandFailed("no scan could be placed");
    write_outputs(o, result);
    if (result.placed_count < 2 && result.scans.size() >= 2)
        report_poor_result("no two scans were joined (1 of " + std::to_string(result.scans.size()) +
                           " placed): the scans need overlapping views; see the reasons above");
    else if (2 * consistency.taken_out > consistency.checked)
        report_poor_result(std::to_string(consistency.taken_out) + " of " +
                           std::to_string(consistency.checked) +
                           " placed scans contradicted the others and were taken out");
}

}  // namespace

void add_register_command(CLI::App& app) {
    auto opts = std::make_shared<RegisterOptions>();
    auto* cmd = app.add_subcommand(
        "register",
        "Register unordered scans without initial poses (global registration of "
        "every pair, pose graph, fine and multi-view refinement); writes the poses "
        "of the placed scans as a Stanford .conf and lists the scans not placed");
    cmd->add_option("scans", opts->scans, "Scans (.ply), any order")
        ->required()
        ->check(CLI::ExistingFile);
    cmd->add_option("--out", opts->out, "Poses (.conf; bmesh FILE tx ty tz qx qy qz qw)")
        ->required();
    cmd->add_option("--merged", opts->merged, "Merged placed scans, world frame (.ply)");
    cmd->add_option("--stats", opts->stats, "Figures per stage, pair and scan (.json)");
    add_sensor_options(cmd, opts->sensor);
    add_region_options(cmd, opts->region);
    cmd->callback([opts] { run_register(*opts); });
}

}  // namespace anascan::cli
