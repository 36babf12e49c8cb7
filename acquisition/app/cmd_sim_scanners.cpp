// anascan sim tof-scan | sl-capture | surface-distance (hidden `sim` group): simulated terrestrial
// time-of-flight scans and structured-light image sequences of the named scenes, with their
// true sensor poses, for tests and accuracy checks.
#include <spdlog/spdlog.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <filesystem>

#include "anascan/processing/core/stopwatch.hpp"
#include "anascan/processing/io/ply.hpp"
#include "anascan/processing/io/stanford_conf.hpp"
#include "anascan/sim/ray_caster.hpp"
#include "anascan/sim/structured_light_renderer.hpp"
#include "anascan/sim/surface_distance.hpp"
#include "anascan/sim/tof_scanner.hpp"
#include "anascan/sim/viewpoints.hpp"
#include "commands.hpp"
#include "sim_scene_builder.hpp"

namespace anascan::cli {
namespace {

namespace fs = std::filesystem;

struct SceneChoice {
    std::string name;
    double step_mm = 0.0;
    long long seed = -1;
    std::string out;
};

struct TofOptions {
    SceneChoice scene;
    sim::TofScannerConfig scanner;
    double azimuth_deg = 30.0, distance_m = 3.5, height_m = 1.5;
    double noise_mm = 7.0;
};

struct SlOptions {
    SceneChoice scene;
    sim::StructuredLightRigConfig rig;
    sim::Viewpoint view{.azimuth_deg = 30.0, .elevation_deg = 35.0, .distance_m = 1.0};
    long long render_seed = 1;
};

struct DistanceOptions {
    std::string cloud, mesh;
    double tolerance_mm = 0.3;
    double max_mm = 10.0;
};

sim::RayCaster make_caster(const sim::Scene& scene) {
    auto caster = sim::RayCaster::create(scene.mesh);
    if (!caster) fail_command(caster.error());
    return std::move(*caster);
}

void run_tof(const TofOptions& o) {
    const sim::Scene scene = build_named_scene(o.scene.name, o.scene.step_mm, o.scene.seed);
    const sim::RayCaster caster = make_caster(scene);
    const Pose T_world_scanner = sim::tripod_pose(scene.T_world_block.translation(), o.azimuth_deg,
                                                  o.distance_m, o.height_m);
    sim::TofScannerConfig scanner = o.scanner;
    scanner.range_noise_sigma_m = o.noise_mm / 1000.0;
    const auto start = std::chrono::steady_clock::now();
    auto result =
        sim::simulate_tof_scan(caster, sim::triangle_albedos(scene), T_world_scanner, scanner);
    if (!result) fail_command(result.error());
    spdlog::info("swept {} x {} rays in {:.2f} s", result->grid.rows, result->grid.cols,
                 seconds_since(start));
    double sum2 = 0.0;
    std::size_t clean = 0, mixed = 0;
    for (std::size_t i = 0; i < result->true_range_m.size(); ++i) {
        if (result->mixed[i]) {
            ++mixed;
            continue;
        }
        const double e =
            result->scan.cloud.positions[i].cast<double>().norm() - result->true_range_m[i];
        sum2 += e * e;
        ++clean;
    }
    if (auto ok = io::write_ply(o.scene.out, result->scan.cloud); !ok) fail_command(ok.error());
    const fs::path conf = fs::path(o.scene.out).replace_extension(".conf");
    io::StanfordConf truth;
    truth.entries.push_back({fs::path(o.scene.out).filename().string(), T_world_scanner});
    if (auto ok = io::write_conf(conf, truth); !ok) fail_command(ok.error());
    std::printf(
        "%s: %zu points (%zu mixed pixels), range error RMS %.2f mm (noise %.2f mm); "
        "true pose in %s\n",
        o.scene.out.c_str(), result->scan.cloud.size(), mixed,
        1000.0 * std::sqrt(sum2 / std::max<std::size_t>(clean, 1)), o.noise_mm, conf.c_str());
}

void run_sl(const SlOptions& o) {
    const sim::Scene scene = build_named_scene(o.scene.name, o.scene.step_mm, o.scene.seed);
    const sim::RayCaster caster = make_caster(scene);
    // Aim at the middle of the block's upper half.
    const Eigen::Vector3d target =
        scene.T_world_block.translation() + Eigen::Vector3d(0, 0, 0.25 * scene.block_size_m.z());
    const sim::StructuredLightRig rig =
        sim::make_structured_light_rig(o.rig, sim::sensor_looking_at(target, o.view));
    sim::StructuredLightRenderConfig render{.seed = static_cast<std::uint64_t>(o.render_seed)};
    render.patterns.width_px = o.rig.projector_width_px;
    render.patterns.height_px = o.rig.projector_height_px;
    const auto start = std::chrono::steady_clock::now();
    auto capture = sim::render_structured_light(caster, sim::triangle_albedos(scene), rig, render);
    if (!capture) fail_command(capture.error());
    spdlog::info("rendered 2 x {} images in {:.2f} s", capture->patterns.size(),
                 seconds_since(start));
    const fs::path dir(o.scene.out);
    if (auto ok = sim::write_structured_light_capture(dir, *capture); !ok) fail_command(ok.error());
    Mesh stone = sim::surface_mesh(scene, sim::SurfaceKind::kStone);
    stone.vertices = transformed(stone.vertices, rig.cam1.T_world_device.inverse());
    if (auto ok = io::write_ply(dir / "stone_in_cam1.ply", stone); !ok) fail_command(ok.error());
    cv::Mat column;
    cv::extractChannel(capture->truth1.projector_xy, column, 0);
    const double lit = cv::countNonZero(column == column);  // NaN (unlit) != NaN.
    std::printf(
        "%s: %zu images per camera (pattern_cam{1,2}_imNN.png), calibration.yml, "
        "stone_in_cam1.ply (metres, cam1 frame); %.0f %% of cam1 pixels lit\n",
        dir.c_str(), capture->patterns.size(),
        100.0 * lit / (rig.cam1.width_px * rig.cam1.height_px));
}

// Distance of every point of a cloud to a ground-truth mesh in the same frame.
void run_distance(const DistanceOptions& o) {
    auto cloud = io::read_ply(o.cloud);
    if (!cloud) fail_command(cloud.error());
    auto mesh = io::read_ply(o.mesh);
    if (!mesh) fail_command(mesh.error());
    if (mesh->triangles.empty()) throw CommandFailed(o.mesh + ": no triangles, not a mesh");
    auto caster =
        sim::RayCaster::create(Mesh{.vertices = mesh->cloud, .triangles = mesh->triangles});
    if (!caster) fail_command(caster.error());
    const auto s = sim::summarize_distances(
        sim::surface_distances(cloud->cloud, Pose::Identity(), *caster, 1e-3 * o.max_mm),
        1e-3 * o.tolerance_mm, 1e-3 * o.max_mm);
    const double within = s.within_fraction * double(s.points);
    const std::size_t near = s.points - s.beyond_max;
    std::printf(
        "%s: %zu points, %.2f %% within %.2f mm of %s, median %.3f mm, RMS %.3f mm (points "
        "beyond %.1f mm count as %.1f mm: %zu), RMS of the closest 95 %% %.3f mm; of the %zu "
        "points within %.1f mm (on the mesh's surface), %.2f %% within %.2f mm\n",
        o.cloud.c_str(), s.points, 100.0 * s.within_fraction, o.tolerance_mm, o.mesh.c_str(),
        1e3 * s.median_m, 1e3 * s.rms_m, o.max_mm, o.max_mm, s.beyond_max, 1e3 * s.rms_best95_m,
        near, o.max_mm, 100.0 * within / double(std::max<std::size_t>(near, 1)), o.tolerance_mm);
}

void add_scene_options(CLI::App* cmd, SceneChoice& s, const char* out_help) {
    cmd->add_option("name", s.name, "Scene name (anascan sim list-scenes)")->required();
    cmd->add_option("--out", s.out, out_help)->required();
    cmd->add_option("--step-mm", s.step_mm, "Block mesh spacing, mm (default: the scene's)")
        ->check(CLI::PositiveNumber);
    cmd->add_option("--scene-seed", s.seed, "Seed of the block's features (default: the scene's)")
        ->check(CLI::NonNegativeNumber);
}

}  // namespace

void add_sim_scanner_commands(CLI::App& sim) {
    auto tof = std::make_shared<TofOptions>();
    auto* t =
        sim.add_subcommand("tof-scan", "Simulated terrestrial ToF scan (Riegl LMS-Z420i-like)");
    add_scene_options(t, tof->scene,
                      "Scan (.ply, scanner frame); the true pose goes to .conf beside it");
    t->add_option("--step-deg", tof->scanner.angular_step_deg,
                  "Angular step, degrees (default 0.1)")
        ->check(CLI::PositiveNumber);
    t->add_option("--noise-mm", tof->noise_mm, "Range noise sigma, mm (default 7)")
        ->check(CLI::NonNegativeNumber);
    t->add_option("--azimuth-deg", tof->azimuth_deg, "Scanner position around the block, degrees");
    t->add_option("--distance-m", tof->distance_m, "Horizontal distance to the block centre, m");
    t->add_option("--height-m", tof->height_m, "Optical centre above the ground, m");
    t->add_option("--seed", tof->scanner.seed, "Noise seed");
    t->callback([tof] { run_tof(*tof); });

    auto sl = std::make_shared<SlOptions>();
    auto* s =
        sim.add_subcommand("sl-capture", "Simulated structured-light images (Gray code + phase)");
    add_scene_options(s, sl->scene, "Output folder for images, calibration.yml, stone_in_cam1.ply");
    s->add_option("--distance-m", sl->view.distance_m, "Rig distance to the target, m (default 1)");
    s->add_option("--azimuth-deg", sl->view.azimuth_deg, "Rig position around the block, degrees");
    s->add_option("--elevation-deg", sl->view.elevation_deg, "Rig elevation, degrees");
    s->add_option("--camera-width", sl->rig.camera_width_px, "Camera width, px (default 1600)");
    s->add_option("--camera-height", sl->rig.camera_height_px, "Camera height, px (default 1200)");
    s->add_option("--seed", sl->render_seed, "Image noise seed")->check(CLI::NonNegativeNumber);
    s->callback([sl] { run_sl(*sl); });

    auto dist = std::make_shared<DistanceOptions>();
    auto* d = sim.add_subcommand(
        "surface-distance", "Distance of a cloud's points to a ground-truth mesh (same frame)");
    d->add_option("cloud", dist->cloud, "Point cloud (.ply)")->required();
    d->add_option("--mesh", dist->mesh, "Ground-truth mesh (.ply with faces)")->required();
    d->add_option("--tolerance-mm", dist->tolerance_mm, "Share of points within this, mm (0.3)")
        ->check(CLI::PositiveNumber);
    d->add_option("--max-mm", dist->max_mm, "Farther points count as this, mm (default 10)")
        ->check(CLI::PositiveNumber);
    d->callback([dist] { run_distance(*dist); });
}

}  // namespace anascan::cli
