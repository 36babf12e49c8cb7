// anascan demo: the end-to-end example the README's first command runs.
#include <spdlog/spdlog.h>

#include <cstdio>
#include <filesystem>

#include "anascan/processing/io/ply.hpp"
#include "anascan/processing/io/stanford_conf.hpp"
#include "anascan/sim/box_stone_scanner.hpp"
#include "assemble_runner.hpp"
#include "commands.hpp"

namespace anascan::cli {
namespace {

namespace fs = std::filesystem;

struct DemoOptions {
    std::string bunny_dir;
    std::string out_dir = "anascan-demo";
};

// Writes simulated scans of a block and their true poses; returns the .conf path.
fs::path write_synthetic_scans(const fs::path& folder) {
    fs::create_directories(folder);
    const std::vector<Scan> scans = sim::scan_box_stone({});
    io::StanfordConf conf;
    for (const Scan& scan : scans) {
        const std::string file = scan.meta.id + ".ply";
        if (auto ok = io::write_ply(folder / file, scan.cloud); !ok) fail_command(ok.error());
        conf.entries.push_back({file, scan.meta.T_world_scan.value_or(Pose::Identity())});
        spdlog::info("simulated {} ({} points)", file, scan.cloud.size());
    }
    const fs::path conf_path = folder / "poses.conf";
    if (auto ok = io::write_conf(conf_path, conf); !ok) fail_command(ok.error());
    return conf_path;
}

fs::path choose_input(const DemoOptions& o, const fs::path& out) {
    if (!o.bunny_dir.empty()) {
        const fs::path bunny_conf = fs::path(o.bunny_dir) / "bun.conf";
        if (!fs::exists(bunny_conf))
            throw CommandFailed("--bunny " + o.bunny_dir + ": " + bunny_conf.string() +
                                " not found; give the folder of the Stanford bunny range scans "
                                "(bun.conf and bun*.ply), or leave --bunny out for the "
                                "synthetic example");
        std::printf("input: Stanford bunny range scans with their ground-truth poses (%s)\n",
                    bunny_conf.c_str());
        return bunny_conf;
    }
    std::printf("input: simulated scans of a 0.8 x 0.5 x 0.4 m block with their true poses\n");
    return write_synthetic_scans(out / "synthetic-scans");
}

void run_demo(const DemoOptions& o) {
    const fs::path out = fs::absolute(o.out_dir);
    std::error_code ec;
    fs::create_directories(out, ec);
    if (ec)
        throw CommandFailed(out.string() + ": cannot create the output folder: " + ec.message());
    AssembleOptions assemble{.conf = choose_input(o, out).string(),
                             .model_out = (out / "model.ply").string(),
                             .report_out = (out / "report.json").string(),
                             .voxel_mm = 0.5};
    run_assemble(assemble);
    std::printf("result: %s (open in MeshLab or CloudCompare), report: %s\n",
                assemble.model_out.c_str(), assemble.report_out.c_str());
}

}  // namespace

void add_demo_command(CLI::App& app) {
    auto opts = std::make_shared<DemoOptions>();
    auto* cmd = app.add_subcommand(
        "demo",
        "End-to-end example: assemble the Stanford bunny scans when --bunny is given "
        "and present, otherwise simulated scans of a block");
    cmd->add_option("--bunny", opts->bunny_dir, "Folder with bun.conf and bun*.ply");
    cmd->add_option("--out", opts->out_dir, "Output folder (default ./anascan-demo)");
    cmd->callback([opts] { run_demo(*opts); });
}

}  // namespace anascan::cli
