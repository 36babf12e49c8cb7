// anascan sim list-monuments | export-monument NAME [--seed S] [--blocks A,B] --out DIR: the
// simulated monument (sim/monument.hpp) as a user would have it after scanning (each block's mesh
// in its fallen pose, DIR/blocks/), the built-pose meshes (DIR/built/) and the truth
// (DIR/truth.json: poses and true adjacent face pairs).
#include <spdlog/spdlog.h>

#include <algorithm>
#include <cstdio>
#include <filesystem>
#include <nlohmann/json.hpp>

#include "anascan/acquisition/blocks/block_features_file.hpp"
#include "anascan/processing/io/ply.hpp"
#include "anascan/sim/monument.hpp"
#include "commands.hpp"

namespace anascan::cli {
namespace {

using namespace anascan::acquisition;  // The blocks folder's files.

struct ExportMonumentOptions {
    std::string name;
    std::string out;
    long long seed = 0;
    double step_mm = 0.0;
    std::vector<std::string> blocks;  ///< Only these blocks' meshes (all when empty).
};

nlohmann::json pose_json(const Pose& T) {
    nlohmann::json rows = nlohmann::json::array();
    for (int r = 0; r < 4; ++r) rows.push_back({T(r, 0), T(r, 1), T(r, 2), T(r, 3)});
    return rows;
}

nlohmann::json truth_json(const sim::Monument& m) {
    nlohmann::json blocks = nlohmann::json::array(), joints = nlohmann::json::array();
    for (const sim::MonumentBlock& b : m.blocks)
        blocks.push_back(
            {{"id", b.id},
             {"course", b.course},
             {"size_m", {b.config.size_m.x(), b.config.size_m.y(), b.config.size_m.z()}},
             {"T_monument_block", pose_json(b.T_monument_block)},
             {"T_ground_block", pose_json(b.T_ground_block)},
             {"clamp_halves", b.config.clamp_holes.size()},
             {"dowels", b.config.dowel_holes.size()}});
    for (const sim::JointPair& j : m.joints)
        joints.push_back(
            {{"a", {{"block", m.blocks[j.a.block].id}, {"face", sim::face_name(j.a.face)}}},
             {"b", {{"block", m.blocks[j.b.block].id}, {"face", sim::face_name(j.b.face)}}},
             {"kind", j.kind == sim::JointKind::kVertical ? "vertical" : "bed"}});
    return {{"monument", m.name},
            {"frames",
             "T_ground_block: pose of blocks/ID.ply vertices (block frame centred, "
             "+y facade, +-x vertical joints, +-z beds); T_monument_block: built pose"},
            {"blocks", blocks},
            {"joints", joints}};
}

void run_export_monument(const ExportMonumentOptions& o) {
    auto config = sim::named_monument(o.name, static_cast<std::uint64_t>(o.seed));
    if (!config) fail_command(config.error());
    if (o.step_mm > 0.0) config->grid_step_m = o.step_mm / 1000.0;
    auto monument = sim::make_monument(*config);
    if (!monument) fail_command(monument.error());
    const std::filesystem::path dir(o.out);
    std::error_code ec;
    std::filesystem::create_directories(dir / "blocks", ec);
    std::filesystem::create_directories(dir / "built", ec);
    if (ec) fail_command({ErrorCode::kIo, dir.string() + ": cannot create: " + ec.message()});
    for (const std::string& id : o.blocks)
        if (std::ranges::none_of(monument->blocks, [&](const auto& b) { return b.id == id; }))
            fail_command(
                {ErrorCode::kInvalidArgument, "--blocks " + id + ": no such block in " + o.name});
    std::size_t vertices = 0;
    for (const sim::MonumentBlock& b : monument->blocks) {
        if (!o.blocks.empty() && std::ranges::count(o.blocks, b.id) == 0) continue;
        const Mesh mesh = sim::block_mesh(b);
        vertices += mesh.vertices.size();
        const io::PlyWriteOptions options{
            .comments = {"anascan sim monument " + o.name + " block " + b.id}};
        if (auto ok = io::write_ply(dir / "blocks" / (b.id + ".ply"),
                                    sim::transformed_mesh(mesh, b.T_ground_block), options);
            !ok)
            fail_command(ok.error());
        if (auto ok = io::write_ply(dir / "built" / (b.id + ".ply"),
                                    sim::transformed_mesh(mesh, b.T_monument_block), options);
            !ok)
            fail_command(ok.error());
        spdlog::info("block {}: {:.2f} x {:.2f} x {:.2f} m, {} vertices", b.id, b.config.size_m.x(),
                     b.config.size_m.y(), b.config.size_m.z(), mesh.vertices.size());
    }
    if (auto ok = write_json_file(dir / "truth.json", truth_json(*monument)); !ok)
        fail_command(ok.error());
    std::printf("%s (seed %llu): %zu blocks, %zu true joints, %zu vertices, in %s\n",
                o.name.c_str(), static_cast<unsigned long long>(config->seed),
                monument->blocks.size(), monument->joints.size(), vertices, o.out.c_str());
}

}  // namespace

void add_sim_monument_commands(CLI::App& sim) {
    auto* list = sim.add_subcommand("list-monuments", "Names of the simulated monument sections");
    list->callback([] {
        for (const sim::MonumentInfo& info : sim::monument_catalog())
            std::printf("%-22s %s\n", info.name.c_str(), info.description.c_str());
    });
    auto opts = std::make_shared<ExportMonumentOptions>();
    auto* cmd = sim.add_subcommand(
        "export-monument",
        "A simulated monument section: fallen block meshes, built meshes and the truth");
    cmd->add_option("name", opts->name, "Section name (anascan sim list-monuments)")->required();
    cmd->add_option("--out", opts->out, "Output folder")->required();
    cmd->add_option("--seed", opts->seed, "Random seed (default: the section's)")
        ->check(CLI::NonNegativeNumber);
    cmd->add_option("--step-mm", opts->step_mm, "Mesh vertex spacing, mm (default 5)")
        ->check(CLI::PositiveNumber);
    cmd->add_option("--blocks", opts->blocks,
                    "Write only these blocks' meshes (the truth lists all)")
        ->delimiter(',');
    cmd->callback([opts] { run_export_monument(*opts); });
}

}  // namespace anascan::cli
