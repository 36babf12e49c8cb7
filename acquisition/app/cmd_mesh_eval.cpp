// anascan mesh eval MESH --truth TRUE.ply: a fragment model against the true surface it was
// scanned from (a simulated stone's mesh): accuracy of the measured-class surface,
// completeness, volume and box, and, with --visibility, whether what the scanner never saw
// from its true poses is classed interpolated.
#include <spdlog/spdlog.h>

#include <cmath>
#include <cstdio>
#include <map>
#include <nlohmann/json.hpp>
#include <numbers>

#include "anascan/processing/core/stopwatch.hpp"
#include "anascan/processing/io/file_bytes.hpp"
#include "anascan/processing/io/mesh_formats.hpp"
#include "anascan/processing/io/ply.hpp"
#include "anascan/processing/io/stanford_conf.hpp"
#include "anascan/processing/registration/fine/fine_registration.hpp"
#include "anascan/processing/surface/mesh_distance.hpp"
#include "anascan/processing/surface/mesh_topology.hpp"
#include "anascan/processing/surface/model_report.hpp"
#include "anascan/processing/surface/truth_comparison.hpp"
#include "anascan/sim/sim_structured_light_scanner.hpp"
#include "anascan/sim/structured_light_rig.hpp"
#include "commands.hpp"

namespace anascan::cli {
namespace {

struct MeshEvalOptions {
    std::string mesh, truth, poses, truth_poses, json;
    bool icp = false, visibility = false;
    std::string sensor = "structured-light";  ///< Or "camera": one device of fov_deg.
    std::vector<double> fov_deg{33.0, 25.0};  ///< For --sensor camera.
    std::vector<double> depth_m{0.3, 3.0};
    std::vector<double> incidence_deg{VisibilityConfig{}.seen_incidence_deg,
                                      VisibilityConfig{}.unseen_incidence_deg};
};

struct ClassedMesh {
    Mesh mesh;
    std::vector<SurfaceClass> triangle_class;  ///< Empty: no class in the file.
};

// A PLY written by `anascan mesh` carries the class per vertex ("interpolated", 0 or 1).
ClassedMesh read_classed_mesh(const std::string& path) {
    ClassedMesh out;
    if (std::filesystem::path(path).extension() != ".ply") {
        auto mesh = io::read_mesh(path);
        if (!mesh) fail_command(mesh.error());
        out.mesh = std::move(*mesh);
        return out;
    }
    auto ply = io::read_ply(path);
    if (!ply) fail_command(ply.error());
    if (ply->triangles.empty()) throw CommandFailed(path + ": no triangles (a point cloud?)");
    out.mesh = {.vertices = std::move(ply->cloud), .triangles = std::move(ply->triangles)};
    for (const io::PlyScalarProperty& p : ply->vertex_scalars) {
        if (p.name != "interpolated") continue;
        std::vector<SurfaceClass> vertex_class(p.values.size());
        for (std::size_t v = 0; v < p.values.size(); ++v)
            vertex_class[v] =
                p.values[v] > 0.5f ? SurfaceClass::kInterpolated : SurfaceClass::kMeasured;
        out.triangle_class = triangle_classes_from_vertices(out.mesh, vertex_class);
    }
    return out;
}

std::map<std::string, Pose> read_poses(const std::string& path) {
    auto conf = io::read_conf(path);
    if (!conf) fail_command(conf.error());
    std::map<std::string, Pose> out;
    for (const io::ConfEntry& e : conf->entries)
        out[std::filesystem::path(e.file).filename().string()] = e.T_world_scan;
    return out;
}

// The mesh's frame to the truth's from the first scan of --poses that --truth-poses has.
Pose pose_alignment(const MeshEvalOptions& o) {
    auto conf = io::read_conf(o.poses);
    if (!conf) fail_command(conf.error());
    const std::map<std::string, Pose> truth = read_poses(o.truth_poses);
    for (const io::ConfEntry& e : conf->entries) {
        const auto it = truth.find(std::filesystem::path(e.file).filename().string());
        if (it == truth.end()) continue;
        std::printf("aligned by the poses of %s (T_truth_mesh = truth pose * pose^-1)\n",
                    e.file.c_str());
        return it->second * e.T_world_scan.inverse();
    }
    throw CommandFailed(o.poses + ": no scan also named in " + o.truth_poses);
}

PointCloud surface_points(const Mesh& mesh, double spacing_m, bool with_normals) {
    PointCloud cloud;
    for (const SurfaceSample& s : sample_surface(mesh, spacing_m)) {
        cloud.positions.push_back(s.position_m.cast<float>());
        if (!with_normals) continue;
        const Eigen::Vector3i& t = mesh.triangles[s.triangle];
        const auto& v = mesh.vertices.positions;
        cloud.normals.push_back((v[t[1]] - v[t[0]]).cross(v[t[2]] - v[t[0]]).normalized());
    }
    return cloud;
}

// Refines the alignment by point-to-plane ICP of the model's surface onto the truth's.
Pose icp_alignment(const Mesh& mesh, const Mesh& truth, const Pose& initial) {
    const PointCloud source = surface_points(mesh, 2e-3, false);
    const PointCloud target = surface_points(truth, 1e-3, true);
    const FineRegistrationResult r = register_fine(
        source, target, initial, {.max_correspondence_distance_m = 0.005, .sample_count = 20000});
    std::printf(
        "ICP of the mesh to the truth: %s, RMS %.3f mm, moved %.3f mm / %.4f deg\n",
        std::string(to_string(r.status)).c_str(), 1e3 * r.rms_m,
        1e3 * (r.T_target_source.translation() - initial.translation()).norm(),
        Eigen::AngleAxisd((initial.rotation().transpose() * r.T_target_source.rotation())).angle() *
            180.0 / 3.14159265358979);
    return r.T_target_source;
}

ModelReport report_of(const Mesh& mesh, std::span<const SurfaceClass> triangle_class) {
    FragmentModel m{.mesh = mesh};
    m.triangle_class.assign(triangle_class.begin(), triangle_class.end());
    if (m.triangle_class.empty()) m.triangle_class.assign(mesh.triangles.size(), {});
    m.vertex_class.assign(mesh.vertices.size(), SurfaceClass::kMeasured);
    m.support_distance_m.assign(mesh.vertices.size(), 0.0f);
    m.support_scans.assign(mesh.vertices.size(), 0);
    return make_model_report(m, {});
}

std::vector<Pose> sensor_views(const std::string& truth_poses) {
    std::vector<Pose> views;
    for (const auto& [name, pose] : read_poses(truth_poses)) views.push_back(pose);
    return views;
}

nlohmann::json figures_json(const TruthComparison& c, const ModelReport& model,
                            const ModelReport& truth) {
    const auto vec = [](const Eigen::Vector3d& v) { return nlohmann::json{v.x(), v.y(), v.z()}; };
    return {{"measured_samples", c.measured_samples},
            {"measured_median_mm", 1e3 * c.measured_median_m},
            {"measured_p95_mm", 1e3 * c.measured_p95_m},
            {"measured_max_mm", 1e3 * c.measured_max_m},
            {"interpolated_samples", c.interpolated_samples},
            {"interpolated_p95_mm", 1e3 * c.interpolated_p95_m},
            {"completeness", c.completeness},
            {"closed", model.closed},
            {"manifold", model.manifold},
            {"components", model.components},
            {"volume_m3", model.volume_m3},
            {"truth_volume_m3", truth.volume_m3},
            {"volume_error", model.volume_m3 / truth.volume_m3 - 1.0},
            {"obb_mm", vec(model.obb_mm)},
            {"truth_obb_mm", vec(truth.obb_mm)},
            {"box_mm", vec(1e3 * c.box_m)},
            {"truth_box_mm", vec(1e3 * c.truth_box_m)}};
}

void print_figures(const TruthComparison& c, const ModelReport& m, const ModelReport& t) {
    std::printf(
        "measured-class surface to the truth: median %.3f mm, p95 %.3f mm, max %.3f mm "
        "(%zu samples)\n",
        1e3 * c.measured_median_m, 1e3 * c.measured_p95_m, 1e3 * c.measured_max_m,
        c.measured_samples);
    std::printf("interpolated surface to the truth: median %.3f mm, p95 %.3f mm (%zu samples)\n",
                1e3 * c.interpolated_median_m, 1e3 * c.interpolated_p95_m, c.interpolated_samples);
    std::printf("completeness: %.2f %% of the truth within 0.5 mm (%zu samples)\n",
                100.0 * c.completeness, c.truth_samples);
    std::printf("closed %s, manifold %s, components %zu\n", m.closed ? "yes" : "no",
                m.manifold ? "yes" : "no", m.components);
    std::printf("volume %.9f m^3, truth %.9f m^3 (%+.3f %%)\n", m.volume_m3, t.volume_m3,
                100.0 * (m.volume_m3 / t.volume_m3 - 1.0));
    std::printf("oriented box %.2f x %.2f x %.2f mm, truth %.2f x %.2f x %.2f mm\n", m.obb_mm.x(),
                m.obb_mm.y(), m.obb_mm.z(), t.obb_mm.x(), t.obb_mm.y(), t.obb_mm.z());
    std::printf("box in the truth's frame %.2f x %.2f x %.2f mm, truth %.2f x %.2f x %.2f mm\n",
                1e3 * c.box_m.x(), 1e3 * c.box_m.y(), 1e3 * c.box_m.z(), 1e3 * c.truth_box_m.x(),
                1e3 * c.truth_box_m.y(), 1e3 * c.truth_box_m.z());
}

VisibilityDevice device_of(const sim::PinholeModel& m, const Pose& T_world_view) {
    const auto full_angle_deg = [](double half_extent_px, double focal_px) {
        return 2.0 * std::atan(half_extent_px / focal_px) * 180.0 / std::numbers::pi;
    };
    return {.T_view_device = T_world_view.inverse() * m.T_world_device,
            .horizontal_fov_deg = full_angle_deg(0.5 * m.width_px, m.fx_px),
            .vertical_fov_deg = full_angle_deg(0.5 * m.height_px, m.fy_px)};
}

// What must see a point for the sensor to measure it. The scan frame (the true poses) of a
// structured-light scan is cam1's: the simulated head's cam2 and projector are placed from it.
std::vector<VisibilityDevice> sensor_devices(const MeshEvalOptions& o) {
    if (o.sensor == "camera")
        return {{.horizontal_fov_deg = o.fov_deg[0], .vertical_fov_deg = o.fov_deg[1]}};
    const sim::StructuredLightRig rig =
        sim::make_structured_light_rig(sim::SimStructuredLightConfig{}.rig, Pose::Identity());
    const Pose& T_rig_cam1 = rig.cam1.T_world_device;
    return {device_of(rig.cam1, T_rig_cam1), device_of(rig.cam2, T_rig_cam1),
            device_of(rig.projector, T_rig_cam1)};
}

// The truth's area by the incidence of its best view, and the share the model classes
// measured: the scanner's response to incidence.
void print_bands(const std::vector<IncidenceBand>& bands) {
    std::printf("truth area by its best view's incidence (all devices), classed measured:\n");
    for (const IncidenceBand& b : bands) {
        if (b.area_m2 <= 0.0) continue;
        const double measured = 100.0 * (1.0 - b.interpolated_m2 / b.area_m2);
        if (b.from_deg >= 90.0)
            std::printf("  out of sight   %8.1f cm^2  %6.2f %%\n", 1e4 * b.area_m2, measured);
        else
            std::printf("  %4.0f-%2.0f deg     %8.1f cm^2  %6.2f %%\n", b.from_deg, b.to_deg,
                        1e4 * b.area_m2, measured);
    }
}

nlohmann::json bands_json(const std::vector<IncidenceBand>& bands) {
    nlohmann::json out = nlohmann::json::array();
    for (const IncidenceBand& b : bands)
        out.push_back({{"from_deg", b.from_deg},
                       {"to_deg", b.to_deg},
                       {"area_m2", b.area_m2},
                       {"interpolated_m2", b.interpolated_m2}});
    return out;
}

nlohmann::json visibility(const MeshEvalOptions& o, const ClassedMesh& model, const Mesh& truth) {
    const VisibilityConfig config{.min_depth_m = o.depth_m[0],
                                  .max_depth_m = o.depth_m[1],
                                  .seen_incidence_deg = o.incidence_deg[0],
                                  .unseen_incidence_deg = o.incidence_deg[1],
                                  .devices = sensor_devices(o)};
    const std::vector<Pose> views = sensor_views(o.truth_poses);
    const VisibilityAgreement a =
        compare_classes_with_visibility(model.mesh, model.triangle_class, truth, views, config);
    print_bands(a.bands);
    const double share_grazing =
        a.grazing_area_m2 > 0.0 ? a.grazing_interpolated_m2 / a.grazing_area_m2 : 0.0;
    std::printf(
        "never seen (beyond %.1f deg) from the %zu true sensor poses: %.1f cm^2, %.2f %% of it "
        "classed interpolated\n",
        config.unseen_incidence_deg, views.size(), 1e4 * a.unseen_area_m2,
        100.0 * a.unseen_interpolated_share());
    std::printf("seen (within %.1f deg): %.1f cm^2, %.2f %% of it classed interpolated\n",
                config.seen_incidence_deg, 1e4 * a.seen_area_m2,
                100.0 * a.seen_interpolated_share());
    std::printf("grazing (between): %.1f cm^2, %.2f %% of it classed interpolated\n",
                1e4 * a.grazing_area_m2, 100.0 * share_grazing);
    std::printf("no model surface within 3 mm: %.1f cm^2 of the unseen, %.1f cm^2 of the seen\n",
                1e4 * a.unseen_missing_m2, 1e4 * a.seen_missing_m2);
    const auto share = [](double part, double whole) { return whole > 0.0 ? part / whole : 0.0; };
    std::printf(
        "completeness (within 0.5 mm, 1 mm samples): %.2f %% of the seen, %.2f %% of the "
        "grazing, %.2f %% of the never seen\n",
        100.0 * share(a.seen_covered_m2, a.seen_area_m2),
        100.0 * share(a.grazing_covered_m2, a.grazing_area_m2),
        100.0 * share(a.unseen_covered_m2, a.unseen_area_m2));
    return {{"views", views.size()},
            {"sensor", o.sensor},
            {"seen_incidence_deg", config.seen_incidence_deg},
            {"unseen_incidence_deg", config.unseen_incidence_deg},
            {"unseen_area_m2", a.unseen_area_m2},
            {"unseen_interpolated_share", a.unseen_interpolated_share()},
            {"seen_area_m2", a.seen_area_m2},
            {"seen_interpolated_share", a.seen_interpolated_share()},
            {"grazing_area_m2", a.grazing_area_m2},
            {"grazing_interpolated_share", share_grazing},
            {"unseen_missing_m2", a.unseen_missing_m2},
            {"seen_missing_m2", a.seen_missing_m2},
            {"seen_covered_m2", a.seen_covered_m2},
            {"grazing_covered_m2", a.grazing_covered_m2},
            {"unseen_covered_m2", a.unseen_covered_m2},
            {"bands", bands_json(a.bands)}};
}

void run(const MeshEvalOptions& o) {
    if (o.poses.empty() != o.truth_poses.empty() && !o.poses.empty())
        throw CommandFailed("--poses needs --truth-poses (the same scans' true poses)");
    if (o.visibility && o.truth_poses.empty())
        throw CommandFailed("--visibility needs --truth-poses (where the sensor stood)");
    ClassedMesh model = read_classed_mesh(o.mesh);
    auto truth = io::read_mesh(o.truth);
    if (!truth) fail_command(truth.error());
    if (model.triangle_class.empty())
        spdlog::warn("{}: no class per vertex: all of it counts as measured", o.mesh);
    Pose T = o.poses.empty() ? Pose::Identity() : pose_alignment(o);
    if (o.icp) T = icp_alignment(model.mesh, *truth, T);
    model.mesh.vertices = transformed(model.mesh.vertices, T);
    const TruthComparison c = compare_with_truth(model.mesh, model.triangle_class, *truth);
    const ModelReport m = report_of(model.mesh, model.triangle_class), t = report_of(*truth, {});
    print_figures(c, m, t);
    nlohmann::json json = figures_json(c, m, t);
    if (o.visibility) json["visibility"] = visibility(o, model, *truth);
    if (o.json.empty()) return;
    if (auto ok = io::write_file_atomically(o.json, json.dump(2) + "\n"); !ok)
        fail_command(ok.error());
    std::printf("report: %s\n", o.json.c_str());
}

}  // namespace

void add_mesh_eval_command(CLI::App& mesh) {
    auto o = std::make_shared<MeshEvalOptions>();
    auto* cmd = mesh.add_subcommand(
        "eval", "A fragment model against the true surface (a simulated stone's mesh)");
    cmd->add_option("mesh", o->mesh, "The model (.ply from `anascan mesh`, .obj or .stl)")
        ->required()
        ->check(CLI::ExistingFile);
    cmd->add_option("--truth", o->truth,
                    "The true surface (`anascan sim export-scene NAME "
                    "--stone-only`)")
        ->required()
        ->check(CLI::ExistingFile);
    cmd->add_option("--poses", o->poses,
                    "The scans' poses in the mesh's frame (`session export --poses`): with "
                    "--truth-poses, the mesh is moved to the truth by the first scan's poses")
        ->check(CLI::ExistingFile);
    cmd->add_option("--truth-poses", o->truth_poses,
                    "The same scans' true poses (`session export --truth-poses`)")
        ->check(CLI::ExistingFile);
    cmd->add_flag("--icp", o->icp, "Refine the alignment by ICP of the mesh onto the truth");
    cmd->add_flag("--visibility", o->visibility,
                  "Also compare the classes with what the true sensor poses could see");
    cmd->add_option("--sensor", o->sensor,
                    "What must see a point for --visibility: structured-light (both cameras "
                    "and the projector of sim:structured-light's head, placed from cam1's "
                    "pose) or camera (one device of --fov-deg)")
        ->check(CLI::IsMember({"structured-light", "camera"}))
        ->capture_default_str();
    cmd->add_option("--fov-deg", o->fov_deg, "Field of view of --sensor camera, full angles")
        ->expected(2);
    cmd->add_option("--depth-m", o->depth_m, "Depth range for --visibility, metres")->expected(2);
    cmd->add_option("--incidence-deg", o->incidence_deg,
                    "For --visibility: seen within the first angle, never seen beyond the "
                    "second, grazing between (degrees)")
        ->expected(2)
        ->check(CLI::Range(0.0, 90.0))
        ->capture_default_str();
    cmd->add_option("--json", o->json, "Write the figures as JSON");
    cmd->callback([o] { run(*o); });
}

}  // namespace anascan::cli
