#include "mesh_runner.hpp"

#include <spdlog/spdlog.h>
#include <sys/resource.h>

#include <cstdio>
#include <nlohmann/json.hpp>

#include "anascan/processing/core/stopwatch.hpp"
#include "anascan/processing/io/file_bytes.hpp"
#include "anascan/processing/io/mesh_formats.hpp"
#include "anascan/processing/surface/model_report.hpp"
#include "commands.hpp"

namespace anascan::cli {
namespace {

SurfaceMode parse_mode(const std::string& text) {
    if (text == "closed") return SurfaceMode::kClosed;
    if (text == "measured") return SurfaceMode::kMeasured;
    throw CommandFailed("--surface must be 'closed' or 'measured', not '" + text + "'");
}

nlohmann::json hole_json(const HoleReport& h) {
    nlohmann::json outline = nlohmann::json::array();
    for (const Eigen::Vector3d& p : h.outline_m) outline.push_back({p.x(), p.y(), p.z()});
    return {{"area_m2", h.area_m2},
            {"perimeter_m", h.perimeter_m},
            {"centroid_m", {h.centroid_m.x(), h.centroid_m.y(), h.centroid_m.z()}},
            {"outline_m", outline}};
}

nlohmann::json report_json(const ModelReport& r, const SurfaceResult& s, const MeshOptions& o,
                           double seconds) {
    const SurfaceDiagnostics& d = s.diagnostics;
    nlohmann::json holes = nlohmann::json::array();
    for (const HoleReport& h : r.holes) holes.push_back(hole_json(h));
    return {
        {"surface", o.surface},
        {"resolution_mm", o.resolution_mm},
        {"vertices", r.vertices},
        {"triangles", r.triangles},
        {"closed", r.closed},
        {"manifold", r.manifold},
        {"components", r.components},
        {"single_component", r.components == 1},
        {"area_m2", r.area_m2},
        {"volume_m3", r.volume_m3},
        {"obb_mm", {r.obb_mm.x(), r.obb_mm.y(), r.obb_mm.z()}},
        {"interpolated_area_share", r.interpolated_area_share},
        {"hole_count", r.holes.size()},
        {"holes", holes},
        {"accuracy_median_mm", 1e3 * r.accuracy_median_m},
        {"accuracy_p95_mm", 1e3 * r.accuracy_p95_m},
        {"accuracy_vertices", r.accuracy_samples},
        {"support_threshold_mm", 1e3 * s.model.support_threshold_m},
        {"input_points", d.input_points},
        {"merged_points", d.merged_points},
        {"scans_with_sensor", d.scans_with_sensor},
        {"spacing_mm", 1e3 * d.spacing_m},
        {"poisson_depth", d.poisson_depth},
        {"poisson_cell_mm", 1e3 * d.cell_m},
        {"poisson_memory_estimate_mb", double(d.estimated_memory_bytes) / 1048576.0},
        {"components_removed", d.components_removed},
        {"triangles_removed", d.triangles_removed},
        {"subdivisions", d.subdivisions},
        {"vertices_fitted", d.vertices_fitted},
        {"median_fit_shift_mm", 1e3 * d.median_fit_shift_m},
        {"seconds",
         {{"merge", d.seconds_merge},
          {"normals", d.seconds_normals},
          {"poisson", d.seconds_poisson},
          {"support", d.seconds_support},
          {"total", seconds},
          {"processor", processor_seconds()}}},
        {"peak_memory_mb", double(peak_memory_bytes()) / 1048576.0},
    };
}

io::PlyWriteOptions ply_options(const FragmentModel& m, bool ascii) {
    io::PlyWriteOptions o;
    o.format = ascii ? io::PlyFormat::kAscii : io::PlyFormat::kBinaryLittleEndian;
    o.comments.push_back("anascan fragment model: red-green-blue by class (orange interpolated)");
    io::PlyScalarProperty dist{.name = "support_distance_m"}, scans{.name = "support_scans"},
        cls{.name = "interpolated"};
    for (std::size_t v = 0; v < m.mesh.vertices.size(); ++v) {
        dist.values.push_back(m.support_distance_m[v]);
        scans.values.push_back(float(m.support_scans[v]));
        cls.values.push_back(m.vertex_class[v] == SurfaceClass::kInterpolated ? 1.0f : 0.0f);
    }
    o.vertex_scalars = {std::move(dist), std::move(scans), std::move(cls)};
    return o;
}

}  // namespace

double processor_seconds() {
    rusage u{};
    getrusage(RUSAGE_SELF, &u);
    return double(u.ru_utime.tv_sec + u.ru_stime.tv_sec) +
           1e-6 * double(u.ru_utime.tv_usec + u.ru_stime.tv_usec);
}

std::size_t peak_memory_bytes() {
    rusage usage{};
    getrusage(RUSAGE_SELF, &usage);
    return static_cast<std::size_t>(usage.ru_maxrss) * 1024;
}

void run_mesh(const std::vector<MeshScanEntry>& entries, const MeshOptions& o) {
    Stopwatch watch;
    const SurfaceConfig config{.resolution_m = o.resolution_mm * 1e-3,
                               .mode = parse_mode(o.surface),
                               .max_memory_bytes = std::size_t(o.max_memory_mb * 1048576.0),
                               .fit_to_points = !o.poisson_vertices,
                               .octree_cell_factor = o.octree_cell_factor};
    auto meshed =
        acquisition::mesh_scans(entries, config, [](std::string_view m) { spdlog::info("{}", m); });
    if (!meshed) fail_command(meshed.error());
    const SurfaceResult& result = meshed->surface;
    const ModelReport report = make_model_report(result.model, result.merged);
    const double seconds = watch.seconds();
    if (auto ok = io::write_mesh(o.out, result.model.mesh, ply_options(result.model, o.ascii)); !ok)
        fail_command(ok.error());
    std::printf(
        "mesh: %s (%s surface, %.2f mm resolution, %.1f s, %.1f s of processor time, peak "
        "memory %.0f MB)\n",
        o.out.c_str(), o.surface.c_str(), o.resolution_mm, seconds, processor_seconds(),
        double(peak_memory_bytes()) / 1048576.0);
    std::fputs(model_report_table(report).c_str(), stdout);
    if (!o.report.empty()) {
        const std::string json = report_json(report, result, o, seconds).dump(2) + "\n";
        if (auto ok = io::write_file_atomically(o.report, json); !ok) fail_command(ok.error());
        std::printf("report: %s\n", o.report.c_str());
    }
}

}  // namespace anascan::cli
