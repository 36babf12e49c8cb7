// anascan blocks features MODEL... --out DIR: block features (method paper §5.1) of each
// model (a mesh, or a point cloud with outward normals): DIR/ID.features.json and
// DIR/ID.features.ply (faces coloured, shared edges blue, holes red). The `blocks` group
// also holds match, accept, reject (cmd_blocks_match.cpp) and eval (cmd_blocks_eval.cpp).
#include <spdlog/spdlog.h>

#include <cstdio>
#include <filesystem>
#include <random>

#include "anascan/acquisition/blocks/block_features_file.hpp"
#include "anascan/processing/core/stopwatch.hpp"
#include "anascan/processing/io/ply.hpp"
#include "commands.hpp"

namespace anascan::cli {
namespace {

using namespace anascan::acquisition;  // The blocks folder's files.

namespace ra = anascan::reassembly;

struct FeaturesOptions {
    std::vector<std::string> models;
    std::string out;
    double noise_mm = 0.0;
    unsigned seed = 1;
};

Rgb8 palette(int i) {
    static constexpr Rgb8 kColours[] = {{230, 159, 0},   {86, 180, 233}, {0, 158, 115},
                                        {240, 228, 66},  {0, 114, 178},  {213, 94, 0},
                                        {204, 121, 167}, {140, 140, 60}};
    return kColours[i % 8];
}

// The model's points coloured by face, with the shared edges and holes drawn as points.
PointCloud features_cloud(const PointCloud& points, const ra::BlockFeatures& f) {
    PointCloud out;
    out.positions = points.positions;
    out.colors.resize(points.size(), Rgb8{120, 120, 120});
    for (std::size_t i = 0; i < f.point_face.size(); ++i)
        if (f.point_face[i] >= 0) out.colors[i] = palette(f.point_face[i]);
    auto mark = [&](const Eigen::Vector3d& p, Rgb8 c) {
        out.positions.push_back(p.cast<float>());
        out.colors.push_back(c);
    };
    for (const ra::FaceEdge& e : f.edges)
        for (double t = -0.5; t <= 0.5; t += 0.002)
            mark(e.point_m + t * e.length_m * e.direction, {0, 0, 255});
    for (const ra::PlanarFace& face : f.faces)
        for (const ra::FaceHole& h : face.holes)
            for (double a = -0.5; a <= 0.5; a += 0.02)
                for (double b = -0.5; b <= 0.5; b += 0.1)
                    mark(h.centre_m + a * h.length_m * face.width_axis +
                             b * h.width_m * face.height_axis,
                         {255, 0, 0});
    return out;
}

Expected<Mesh> read_model(const std::string& path, const FeaturesOptions& o) {
    auto ply = io::read_ply(path);
    if (!ply) return Unexpected(ply.error());
    Mesh mesh{.vertices = std::move(ply->cloud), .triangles = std::move(ply->triangles)};
    if (o.noise_mm > 0.0) {  // Test aid: noise on the positions; normals follow the mesh.
        std::mt19937 rng(o.seed);
        std::normal_distribution<float> noise(0.0f, float(o.noise_mm / 1000.0));
        for (Eigen::Vector3f& p : mesh.vertices.positions)
            p += Eigen::Vector3f(noise(rng), noise(rng), noise(rng));
    }
    return mesh;
}

void run_features(const FeaturesOptions& o) {
    std::error_code ec;
    std::filesystem::create_directories(o.out, ec);
    if (ec) fail_command({ErrorCode::kIo, o.out + ": cannot create: " + ec.message()});
    int failed = 0;
    for (const std::string& path : o.models) {
        NamedBlockFeatures block{.id = std::filesystem::path(path).stem().string(), .source = path};
        auto mesh = read_model(path, o);
        if (!mesh) fail_command(mesh.error());
        const Stopwatch watch;
        const ra::BlockFeatureConfig config;
        block.features = mesh->triangles.empty()
                             ? ra::extract_block_features(mesh->vertices, config)
                             : ra::extract_block_features(*mesh, config);
        const double seconds = watch.seconds();
        const ra::BlockFeatures& f = block.features;
        std::size_t holes = 0;
        for (const auto& face : f.faces) holes += face.holes.size();
        std::printf("%-10s %-14s %zu faces, %zu edges, %zu holes, %zu points, %.2f s: %s\n",
                    block.id.c_str(), ra::to_string(f.status), f.faces.size(), f.edges.size() / 2,
                    holes, f.num_points, seconds, f.message.c_str());
        failed += f.matchable() ? 0 : 1;
        const std::filesystem::path base = std::filesystem::path(o.out) / block.id;
        if (auto ok = write_json_file(base.string() + ".features.json", to_json(block)); !ok)
            fail_command(ok.error());
        if (auto ok =
                io::write_ply(base.string() + ".features.ply", features_cloud(mesh->vertices, f));
            !ok)
            fail_command(ok.error());
    }
    if (failed > 0)
        spdlog::warn("{} of {} blocks cannot be matched (see their status)", failed,
                     o.models.size());
}

}  // namespace

void add_blocks_command(CLI::App& app) {
    auto* blocks =
        app.add_subcommand("blocks", "Block features, neighbour proposals and their evaluation");
    blocks->require_subcommand(1);
    auto opts = std::make_shared<FeaturesOptions>();
    auto* cmd = blocks->add_subcommand(
        "features", "Planar faces, adjacency, roughness and holes of block models");
    cmd->add_option("models", opts->models, "Block models (PLY mesh or cloud with normals)")
        ->required()
        ->check(CLI::ExistingFile);
    cmd->add_option("--out", opts->out, "Output folder (ID.features.json, ID.features.ply)")
        ->required();
    cmd->add_option("--noise-mm", opts->noise_mm,
                    "Add Gaussian noise of this sigma to mesh vertices (tests)")
        ->check(CLI::NonNegativeNumber);
    cmd->add_option("--seed", opts->seed, "Seed of the added noise");
    cmd->callback([opts] { run_features(*opts); });
    add_blocks_match_commands(*blocks);
    add_blocks_eval_command(*blocks);
    add_blocks_assemble_command(*blocks);
}

}  // namespace anascan::cli
