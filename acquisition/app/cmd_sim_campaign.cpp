// anascan sim campaign --stones S --scans-per-stone K --out DIR (hidden `sim` group): a
// simulated campaign. Procedural stone blocks (sizes, finishes and seeds differ from the
// scene catalogue's), each scanned from K viewpoints around it (some from below, as after
// turning the stone over) by the simulated time-of-flight scanner at close range, every
// scan moved to a random pose and written as plain points (x y z: no normals, no sensor)
// under a shuffled name that carries no stone; DIR/truth.json holds each file's stone and
// true pose, DIR/list.txt the files. --extra-conf adds the scans of a .conf (e.g. the
// Stanford bunny) as one more stone; --background-scans adds scans of bare ground.
#include <spdlog/spdlog.h>

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <random>

#include "anascan/processing/evaluation/pose_sampling.hpp"
#include "anascan/processing/io/file_bytes.hpp"
#include "anascan/processing/io/ply.hpp"
#include "anascan/processing/io/stanford_conf.hpp"
#include "anascan/sim/ray_caster.hpp"
#include "anascan/sim/stone_block.hpp"
#include "anascan/sim/tof_scanner.hpp"
#include "anascan/sim/viewpoints.hpp"
#include "commands.hpp"
#include "scan_preparation.hpp"

namespace anascan::cli {
namespace {

namespace fs = std::filesystem;
using nlohmann::json;

struct SimCampaignOptions {
    int stones = 3;
    int scans_per_stone = 8;
    int background_scans = 0;
    std::string extra_conf;
    unsigned seed = 1;
    double spacing_mm = 2.5;  ///< Sample spacing at the block.
    double noise_mm = 0.2;
    /// Mixed pixels at depth edges (probability; a close-range structured-light scanner has
    /// none, a terrestrial time-of-flight scanner many).
    double mixed_pixels = 0.0;
    std::string out;
};

/// A scan in a stone's frame before the random move, or of nothing in particular.
struct RawScan {
    PointCloud cloud;  ///< Points, file frame before the move (T_stone_raw maps them).
    Pose T_stone_raw = Pose::Identity();
    int stone = -1;  ///< -1: no stone (background).
};

double uniform(std::mt19937& rng, double lo, double hi) {
    return std::uniform_real_distribution<double>(lo, hi)(rng);
}

sim::StoneBlockConfig block_config(std::mt19937& rng, int stone) {
    sim::StoneBlockConfig b;
    b.size_m = {uniform(rng, 0.5, 1.0), uniform(rng, 0.3, 0.6), uniform(rng, 0.25, 0.5)};
    b.grid_step_m = 0.004;
    b.seed = 1000 + static_cast<std::uint64_t>(stone);
    const double scale = uniform(rng, 0.6, 1.4);
    for (sim::FaceFinish& f : b.finishes) f.amplitude_m *= scale;
    b.ornament.enabled = stone % 2 == 0;
    b.chip_count = 4 + stone % 6;
    return b;
}

std::vector<RawScan> scan_stone(std::mt19937& rng, int stone, const SimCampaignOptions& o) {
    const Mesh mesh = sim::make_stone_block(block_config(rng, stone));
    auto caster = sim::RayCaster::create(mesh);
    if (!caster) fail_command(caster.error());
    const std::array<double, 3> elevations_deg{35.0, 10.0, -30.0};
    std::vector<RawScan> scans;
    for (int k = 0; k < o.scans_per_stone; ++k) {
        const double distance_m = uniform(rng, 1.2, 1.6);
        const double elevation = elevations_deg[static_cast<std::size_t>(k) % 3];
        const double azimuth = 360.0 * k / o.scans_per_stone + uniform(rng, -10.0, 10.0);
        const double height_m = distance_m * std::tan(elevation * M_PI / 180.0);
        const Pose T = sim::tripod_pose(Eigen::Vector3d::Zero(), azimuth, distance_m, height_m);
        const sim::TofScannerConfig tof{
            .angular_step_deg = o.spacing_mm / 1e3 / distance_m * 180.0 / M_PI,
            .azimuth_start_deg = -30.0,
            .azimuth_span_deg = 60.0,
            .elevation_min_deg = -elevation - 30.0,
            .elevation_max_deg = -elevation + 30.0,
            .min_range_m = 0.3,
            .range_noise_sigma_m = o.noise_mm / 1e3,
            .mixed_pixel_probability = o.mixed_pixels,
            .seed = o.seed * 7919u + static_cast<unsigned>(stone * 100 + k)};
        auto scan = sim::simulate_tof_scan(*caster, {}, T, tof);
        if (!scan) fail_command(scan.error());
        scans.push_back({.cloud = std::move(scan->scan.cloud),
                         .T_stone_raw = scan->scan.meta.T_world_scan.value_or(T),
                         .stone = stone});
    }
    return scans;
}

std::vector<RawScan> conf_scans(const std::string& conf_path, int stone) {
    auto conf = io::read_conf(conf_path);
    if (!conf) fail_command(conf.error());
    std::vector<RawScan> scans;
    for (const io::ConfEntry& entry : conf->entries) {
        auto cloud = load_ply_cloud((fs::path(conf_path).parent_path() / entry.file).string());
        if (!cloud) fail_command(cloud.error());
        scans.push_back(
            {.cloud = std::move(*cloud), .T_stone_raw = entry.T_world_scan, .stone = stone});
    }
    return scans;
}

/// Bare ground seen from above: a noisy plane of 0.8 m x 0.8 m at the sample spacing.
RawScan ground_scan(std::mt19937& rng, const SimCampaignOptions& o) {
    RawScan scan;
    std::normal_distribution<double> noise(0.0, o.noise_mm / 1e3);
    const double step = o.spacing_mm / 1e3;
    for (double x = -0.4; x < 0.4; x += step) {
        for (double y = -0.4; y < 0.4; y += step) {
            scan.cloud.positions.emplace_back(x, y, noise(rng));
        }
    }
    return scan;
}

/// The cloud moved by T and with its points relative to zero, without normals.
PointCloud plain_points(const PointCloud& cloud, const Pose& T_moved_raw) {
    PointCloud moved = transformed(cloud, T_moved_raw);
    for (Eigen::Vector3f& p : moved.positions)
        p = (moved.origin_m + p.cast<double>()).cast<float>();
    moved.origin_m.setZero();
    moved.normals.clear();
    return moved;
}

json pose_json(const Pose& T) {
    json rows = json::array();
    for (int i = 0; i < 4; ++i)
        for (int j = 0; j < 4; ++j) rows.push_back(T.matrix()(i, j));
    return rows;
}

void write_campaign(std::vector<RawScan> scans, std::mt19937& rng, const SimCampaignOptions& o) {
    std::shuffle(scans.begin(), scans.end(), rng);
    json truth = json::array();
    std::string list;
    for (std::size_t i = 0; i < scans.size(); ++i) {
        char name[32];
        std::snprintf(name, sizeof name, "scan_%04zu.ply", i);
        const Pose T_moved_raw = sample_random_pose(rng, 0.5);
        if (auto ok =
                io::write_ply(fs::path(o.out) / name, plain_points(scans[i].cloud, T_moved_raw));
            !ok) {
            fail_command(ok.error());
        }
        truth.push_back(
            {{"file", name},
             {"stone", scans[i].stone},
             {"T_stone_scan", pose_json(scans[i].T_stone_raw * T_moved_raw.inverse())}});
        list += std::string(name) + "\n";
    }
    const fs::path out(o.out);
    if (auto ok =
            io::write_file_atomically(out / "truth.json", json{{"scans", truth}}.dump(1) + "\n");
        !ok) {
        fail_command(ok.error());
    }
    if (auto ok = io::write_file_atomically(out / "list.txt", list); !ok) fail_command(ok.error());
    std::printf("%zu scans in %s (truth.json, list.txt)\n", scans.size(), o.out.c_str());
}

void run_sim_campaign(const SimCampaignOptions& o) {
    std::error_code ec;
    fs::create_directories(o.out, ec);
    if (ec) throw CommandFailed(o.out + ": cannot create the folder: " + ec.message());
    std::mt19937 rng(o.seed);
    std::vector<RawScan> scans;
    for (int s = 0; s < o.stones; ++s) {
        spdlog::info("stone {} of {}", s + 1, o.stones);
        for (RawScan& scan : scan_stone(rng, s, o)) scans.push_back(std::move(scan));
    }
    if (!o.extra_conf.empty()) {
        for (RawScan& scan : conf_scans(o.extra_conf, o.stones)) scans.push_back(std::move(scan));
    }
    for (int b = 0; b < o.background_scans; ++b) scans.push_back(ground_scan(rng, o));
    write_campaign(std::move(scans), rng, o);
}

}  // namespace

void add_sim_campaign_command(CLI::App& sim) {
    auto o = std::make_shared<SimCampaignOptions>();
    auto* cmd =
        sim.add_subcommand("campaign", "A simulated campaign of many stones with its truth");
    cmd->add_option("--stones", o->stones, "Procedural stone blocks")->check(CLI::Range(0, 10000));
    cmd->add_option("--scans-per-stone", o->scans_per_stone, "Scans of each block")
        ->check(CLI::Range(1, 1000));
    cmd->add_option("--extra-conf", o->extra_conf,
                    "Scans and poses (.conf) added as one more stone")
        ->check(CLI::ExistingFile);
    cmd->add_option("--background-scans", o->background_scans, "Scans of bare ground (no stone)");
    cmd->add_option("--spacing-mm", o->spacing_mm, "Sample spacing on the blocks (mm)");
    cmd->add_option("--noise-mm", o->noise_mm, "Range noise, standard deviation (mm)");
    cmd->add_option("--mixed-pixels", o->mixed_pixels,
                    "Probability of a mixed pixel at depth edges");
    cmd->add_option("--seed", o->seed, "Random seed");
    cmd->add_option("--out", o->out, "Output folder")->required();
    cmd->callback([o] { run_sim_campaign(*o); });
}

}  // namespace anascan::cli
