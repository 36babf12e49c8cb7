// anascan sim list-scenes | export-scene NAME --out MESH.ply (hidden `sim` group): the
// procedural scenes of the simulator and their ground-truth meshes.
#include <spdlog/spdlog.h>

#include <cstdio>

#include "anascan/processing/io/ply.hpp"
#include "anascan/sim/scene.hpp"
#include "commands.hpp"
#include "sim_scene_builder.hpp"

namespace anascan::cli {
namespace {

struct ExportSceneOptions {
    std::string name;
    std::string out;
    bool stone_only = false;
    double step_mm = 0.0;
    long long seed = -1;
};

void run_list_scenes() {
    for (const sim::SceneInfo& info : sim::scene_catalog())
        std::printf("%-24s %s\n", info.name.c_str(), info.description.c_str());
}

}  // namespace

sim::Scene build_named_scene(const std::string& name, double step_mm, long long seed) {
    auto config = sim::named_scene(name);
    if (!config) fail_command(config.error());
    if (step_mm > 0.0) config->block.grid_step_m = step_mm / 1000.0;
    if (seed >= 0) config->block.seed = static_cast<std::uint64_t>(seed);
    spdlog::info("building scene {} ({:.1f} mm mesh)", name, 1000.0 * config->block.grid_step_m);
    return sim::make_scene(*config);
}

namespace {

void run_export_scene(const ExportSceneOptions& o) {
    const sim::Scene scene = build_named_scene(o.name, o.step_mm, o.seed);
    const Mesh mesh =
        o.stone_only ? sim::surface_mesh(scene, sim::SurfaceKind::kStone) : scene.mesh;
    const Eigen::Matrix4d T = scene.T_world_block.matrix();
    io::PlyWriteOptions options{.comments = {"anascan sim scene " + o.name}};
    char pose[256];
    std::snprintf(pose, sizeof(pose), "T_world_block %g %g %g %g %g %g %g %g %g %g %g %g", T(0, 0),
                  T(0, 1), T(0, 2), T(0, 3), T(1, 0), T(1, 1), T(1, 2), T(1, 3), T(2, 0), T(2, 1),
                  T(2, 2), T(2, 3));
    options.comments.push_back(pose);
    if (auto ok = io::write_ply(o.out, mesh, options); !ok) fail_command(ok.error());
    std::printf("%s: %zu vertices, %zu triangles (%s, world frame, metres)\n", o.out.c_str(),
                mesh.vertices.size(), mesh.triangles.size(),
                o.stone_only ? "stone only" : "stone, ground and tent");
    std::printf("block %.3f x %.3f x %.3f m, centre at (%.3f, %.3f, %.3f) m\n",
                scene.block_size_m.x(), scene.block_size_m.y(), scene.block_size_m.z(), T(0, 3),
                T(1, 3), T(2, 3));
}

}  // namespace

void add_sim_scene_commands(CLI::App& sim) {
    auto* list = sim.add_subcommand("list-scenes", "Names of the simulated scenes");
    list->callback([] { run_list_scenes(); });
    auto opts = std::make_shared<ExportSceneOptions>();
    auto* cmd = sim.add_subcommand(
        "export-scene", "Ground-truth mesh of a simulated scene as PLY (see list-scenes)");
    cmd->add_option("name", opts->name, "Scene name (anascan sim list-scenes)")->required();
    cmd->add_option("--out", opts->out, "Output mesh (.ply, binary)")->required();
    cmd->add_flag("--stone-only", opts->stone_only, "Only the block, without ground and tent");
    cmd->add_option("--step-mm", opts->step_mm,
                    "Mesh vertex spacing on the block, mm (default: the scene's)")
        ->check(CLI::PositiveNumber);
    cmd->add_option("--seed", opts->seed,
                    "Random seed of the block's features (default: the scene's)")
        ->check(CLI::NonNegativeNumber);
    cmd->callback([opts] { run_export_scene(*opts); });
    add_sim_scanner_commands(sim);
    add_sim_monument_commands(sim);
}

}  // namespace anascan::cli
