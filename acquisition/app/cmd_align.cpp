// anascan align SOURCE.ply TARGET.ply: pairwise registration (global + fine, or fine from
// --init), T maps source points into the target frame.
#include <spdlog/spdlog.h>

#include <cstdio>
#include <nlohmann/json.hpp>

#include "anascan/processing/global_registration.hpp"
#include "anascan/processing/io/file_bytes.hpp"
#include "anascan/processing/io/xf.hpp"
#include "anascan/processing/scan_registration.hpp"
#include "commands.hpp"
#include "scan_preparation.hpp"

namespace anascan::cli {
namespace {

struct AlignOptions {
    std::string source;
    std::string target;
    std::string init;
    std::string out;
    std::string stats;
    SensorOptions sensor;
};

PointCloud load_prepared(const std::string& path, const SensorOptions& sensor) {
    auto cloud = load_ply_cloud(path);
    if (!cloud) fail_command(cloud.error());
    if (prepare_scan(*cloud, sensor_origin(sensor), {}) == 0) {
        throw CommandFailed(path + ": no finite points with a normal");
    }
    return std::move(*cloud);
}

/// Why a fine result is not verified (the global registration's thresholds); empty if it is.
std::string rejection(const FineRegistrationResult& fine) {
    const GlobalRegistrationConfig limits{};
    if (fine.status == FineRegistrationStatus::kInsufficientOverlap ||
        fine.status == FineRegistrationStatus::kInvalidInput) {
        return std::string(to_string(fine.status)) + (fine.message.empty() ? "" : ": ") +
               fine.message;
    }
    if (fine.status == FineRegistrationStatus::kDegenerate) return "degenerate constraint";
    if (fine.overlap_fraction < limits.min_overlap_fraction) return "overlap too small";
    if (fine.normal_deviation_deg.value_or(0.0) > limits.max_normal_deviation_deg) {
        return "normals disagree";
    }
    return {};
}

void print_fine(const FineRegistrationResult& fine, const std::string& status, double time_s) {
    std::printf("status: %s\n", status.c_str());
    std::printf("rms: %.4f mm\n", 1e3 * fine.rms_m);
    std::printf("overlap: %.1f %%\n", 100.0 * fine.overlap_fraction);
    std::printf("normal deviation: %.2f deg\n", fine.normal_deviation_deg.value_or(-1.0));
    std::printf("degeneracy (smallest/largest eigenvalue): %.4g\n",
                fine.degeneracy.eigenvalue_ratio);
    std::printf("time: %.2f s\n", time_s);
}

void write_outputs(const AlignOptions& o, const FineRegistrationResult& fine,
                   const std::string& status, double time_s) {
    if (!o.out.empty()) {
        if (auto ok = io::write_xf(o.out, fine.T_target_source); !ok) fail_command(ok.error());
        std::printf("transform: %s\n", o.out.c_str());
    }
    if (o.stats.empty()) return;
    const nlohmann::json doc = {{"status", status},
                                {"fine_status", std::string(to_string(fine.status))},
                                {"rms_m", fine.rms_m},
                                {"overlap", fine.overlap_fraction},
                                {"normal_deviation_deg", fine.normal_deviation_deg.value_or(-1.0)},
                                {"degeneracy", fine.degeneracy.eigenvalue_ratio},
                                {"iterations", fine.iterations},
                                {"time_s", time_s}};
    if (auto ok = io::write_file_atomically(o.stats, doc.dump(2) + "\n"); !ok) {
        fail_command(ok.error());
    }
    std::printf("stats: %s\n", o.stats.c_str());
}

void run_align(const AlignOptions& o) {
    const PointCloud source = load_prepared(o.source, o.sensor);
    const PointCloud target = load_prepared(o.target, o.sensor);
    Pose initial = Pose::Identity();
    double global_time_s = 0.0;
    std::string status = "fine only";
    if (o.init.empty()) {
        spdlog::info("global registration of {} onto {}", o.source, o.target);
        const GlobalRegistrationResult global = register_global(source, target, {});
        global_time_s = global.timing.total_s;
        status = "global " + std::string(to_string(global.status));
        if (global.status != GlobalRegistrationStatus::kSuccess) {
            std::printf("status: %s\ntime: %.2f s\n", status.c_str(), global_time_s);
            throw CommandFailed("not verified: global registration " +
                                std::string(to_string(global.status)) + ": " + global.message);
        }
        initial = global.T_target_source;
    } else {
        auto init = io::read_xf(o.init);
        if (!init) fail_command(init.error());
        initial = *init;
    }
    const FineRegistrationResult fine = register_fine(source, target, initial, {});
    const std::string why = rejection(fine);
    status += why.empty() ? ", verified" : ", NOT verified (" + why + ")";
    print_fine(fine, status, global_time_s + fine.time_s);
    if (!why.empty()) throw CommandFailed("not verified: " + why);
    write_outputs(o, fine, status, global_time_s + fine.time_s);
}

}  // namespace

void add_align_command(CLI::App& app) {
    auto opts = std::make_shared<AlignOptions>();
    auto* cmd = app.add_subcommand(
        "align",
        "Register SOURCE onto TARGET: global + fine registration, or fine only from "
        "--init; the transform maps source points into the target frame");
    cmd->add_option("source", opts->source, "Source scan (.ply)")
        ->required()
        ->check(CLI::ExistingFile);
    cmd->add_option("target", opts->target, "Target scan (.ply)")
        ->required()
        ->check(CLI::ExistingFile);
    cmd->add_option("--init", opts->init, "Initial transform (.xf, 4x4 row-major): fine only")
        ->check(CLI::ExistingFile);
    cmd->add_option("--out", opts->out, "Result transform (.xf, 4x4 row-major)");
    cmd->add_option("--stats", opts->stats, "Figures (.json)");
    add_sensor_options(cmd, opts->sensor);
    cmd->callback([opts] { run_align(*opts); });
}

}  // namespace anascan::cli
