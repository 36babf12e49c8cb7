// anascan mesh POSES.conf --out MESH: the fragment model of scans placed by a .conf.
#include "anascan/processing/io/stanford_conf.hpp"
#include "commands.hpp"
#include "mesh_runner.hpp"
#include "scan_preparation.hpp"

namespace anascan::cli {
namespace {

struct MeshCommandOptions {
    std::string conf;
    MeshOptions mesh;
    SensorOptions sensor;
};

void run(const MeshCommandOptions& o) {
    if (o.conf.empty() || o.mesh.out.empty())
        throw CommandFailed("mesh: give POSES.conf and --out MESH (or `mesh eval`)");
    auto conf = io::read_conf(o.conf);
    if (!conf) fail_command(conf.error());
    if (conf->entries.empty()) throw CommandFailed(o.conf + ": no bmesh lines: nothing to mesh");
    const std::filesystem::path folder = std::filesystem::path(o.conf).parent_path();
    std::vector<MeshScanEntry> entries;
    for (const io::ConfEntry& e : conf->entries) {
        entries.push_back({folder / e.file, e.T_world_scan, sensor_origin(o.sensor)});
    }
    run_mesh(entries, o.mesh);
}

}  // namespace

void add_mesh_options(CLI::App* cmd, MeshOptions& o) {
    cmd->add_option("--resolution-mm", o.resolution_mm,
                    "Finest surface cell, mm (the octree depth follows from it)")
        ->check(CLI::PositiveNumber);
    cmd->add_option("--surface", o.surface,
                    "closed: watertight, interpolated parts kept and flagged (default); "
                    "measured: interpolated triangles removed, holes left open and reported")
        ->check(CLI::IsMember({"closed", "measured"}));
    cmd->add_option("--report", o.report, "Model report (.json)");
    cmd->add_flag("--ascii", o.ascii, "Write an ASCII PLY (default binary)");
    cmd->add_option("--max-memory-mb", o.max_memory_mb,
                    "Memory budget of the Poisson step, MB (the octree is coarsened to fit)")
        ->check(CLI::PositiveNumber);
    cmd->add_flag("--poisson-vertices", o.poisson_vertices,
                  "Leave the vertices where Poisson's octree put them, for comparison "
                  "(default: measured vertices are moved onto the points' local surface)");
    cmd->add_option("--octree-cell-factor", o.octree_cell_factor,
                    "Poisson's finest cell may be up to this many times --resolution-mm; the "
                    "mesh is then subdivided and fitted to the points (1: Poisson's own detail)")
        ->check(CLI::Range(1.0, 16.0));
}

void add_mesh_command(CLI::App& app) {
    auto o = std::make_shared<MeshCommandOptions>();
    auto* cmd = app.add_subcommand(
        "mesh",
        "Fragment model of scans placed by a Stanford .conf: screened Poisson surface whose "
        "vertices and triangles say what was measured and what was filled in");
    cmd->add_option("conf", o->conf, "Pose file (bmesh FILE tx ty tz qx qy qz qw)")
        ->check(CLI::ExistingFile);
    cmd->add_option("--out", o->mesh.out, "Mesh (.ply, .obj or .stl)");
    add_mesh_options(cmd, o->mesh);
    add_sensor_options(cmd, o->sensor);
    add_mesh_eval_command(*cmd);
    cmd->callback([o, cmd] {
        if (cmd->got_subcommand("eval")) return;
        run(*o);
    });
}

}  // namespace anascan::cli
