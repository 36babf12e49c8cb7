// anascan sim move-scans IN.conf --seed S --out DIR (hidden): copies of the scans of a
// .conf, each moved by a random rigid transform (uniform rotation, up to 0.5 m translation)
// and written as plain points (x y z only: no normals, no sensor position, as Open3D or
// CloudCompare export them), and DIR/truth.conf with the moved files' true poses, for
// registration checks. Prints the file names shuffled, one a line.
#include <spdlog/spdlog.h>

#include <Eigen/Geometry>
#include <algorithm>
#include <cstdio>
#include <filesystem>
#include <random>

#include "anascan/processing/evaluation/pose_sampling.hpp"
#include "anascan/processing/io/ply.hpp"
#include "anascan/processing/io/stanford_conf.hpp"
#include "commands.hpp"
#include "scan_preparation.hpp"

namespace anascan::cli {
namespace {

namespace fs = std::filesystem;

struct MoveOptions {
    std::string conf;
    unsigned seed = 1;
    std::string out_dir;
};

/// The cloud with its points relative to zero: a plain export carries no frame origin (ours
/// would be where the original frame's origin moved to).
PointCloud without_origin(PointCloud cloud) {
    for (Eigen::Vector3f& p : cloud.positions) {
        p = (cloud.origin_m + p.cast<double>()).cast<float>();
    }
    cloud.origin_m.setZero();
    return cloud;
}

void run_move(const MoveOptions& o) {
    auto conf = io::read_conf(o.conf);
    if (!conf) fail_command(conf.error());
    std::mt19937 rng(o.seed);
    std::error_code ec;
    fs::create_directories(o.out_dir, ec);
    if (ec) throw CommandFailed(o.out_dir + ": cannot create the folder: " + ec.message());
    std::vector<std::string> names;
    io::StanfordConf
        truth;  // Poses of the moved files: T_world_moved = T_world_scan · T_scan_moved.
    for (const io::ConfEntry& entry : conf->entries) {
        auto cloud = load_ply_cloud((fs::path(o.conf).parent_path() / entry.file).string());
        if (!cloud) fail_command(cloud.error());
        // Plain points: normals of the original frame would carry the side the scanner saw
        // from, which a moved file's reader cannot know.
        cloud->normals.clear();
        const fs::path out = fs::path(o.out_dir) / fs::path(entry.file).filename();
        const Pose T_moved_scan = sample_random_pose(rng, 0.5);
        auto ok = io::write_ply(out, without_origin(transformed(*cloud, T_moved_scan)));
        if (!ok) fail_command(ok.error());
        names.push_back(fs::path(entry.file).filename().string());
        truth.entries.push_back({names.back(), entry.T_world_scan * T_moved_scan.inverse()});
        spdlog::info("moved {}", out.string());
    }
    const fs::path truth_path = fs::path(o.out_dir) / "truth.conf";
    if (auto ok = io::write_conf(truth_path, truth); !ok) fail_command(ok.error());
    std::shuffle(names.begin(), names.end(), rng);
    for (const std::string& name : names) std::printf("%s\n", name.c_str());
}

}  // namespace

void add_sim_command(CLI::App& app) {
    auto opts = std::make_shared<MoveOptions>();
    auto* sim = app.add_subcommand("sim", "Simulation helpers for tests")->group("");
    sim->require_subcommand(1);
    auto* cmd = sim->add_subcommand("move-scans", "Randomly moved copies of a .conf's scans");
    cmd->add_option("conf", opts->conf, "Scans and poses (.conf)")
        ->required()
        ->check(CLI::ExistingFile);
    cmd->add_option("--seed", opts->seed, "Random seed")->required();
    cmd->add_option("--out", opts->out_dir, "Output folder")->required();
    cmd->callback([opts] { run_move(*opts); });
    add_sim_scene_commands(*sim);
    add_sim_campaign_command(*sim);
}

}  // namespace anascan::cli
