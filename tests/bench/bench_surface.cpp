// Fragment models, ours against Open3D's documented path in the same run, on scans placed
// by a .conf, evaluated against a reference mesh:
//   anascan_bench_surface POSES.conf REFERENCE.ply [--resolution-mm R] [--sensor X Y Z]
//                         [--reference-samples] [--skip-open3d] [--poisson-sample-cells C]
//                         [--poisson-scale S] [--poisson-threads N] [--linear-fit]
//                         [--max-memory-mb M] [--no-fit-to-points]
//                         [--octree-cell-factor F]
// Open3D's path: normals from 20 nearest neighbours per scan oriented toward the scanner,
// screened Poisson at depth 10, the 1% lowest-density vertices trimmed.
// Accuracy: mesh-surface samples within 1 mm of a scan point, distance to the reference.
// Completeness: reference vertices (or, with --reference-samples, reference-surface samples)
// within 0.5 mm of the mesh. Times are whole-process (load excluded, identical for both).
#include <open3d/geometry/KDTreeSearchParam.h>
#include <open3d/geometry/PointCloud.h>
#include <open3d/geometry/TriangleMesh.h>
#include <sys/resource.h>

#include <algorithm>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <string>
#include <vector>

#include "anascan/processing/core/pose.hpp"
#include "anascan/processing/core/stopwatch.hpp"
#include "anascan/processing/io/mesh_formats.hpp"
#include "anascan/processing/io/stanford_conf.hpp"
#include "anascan/processing/spatial/kdtree.hpp"
#include "anascan/processing/surface/mesh_distance.hpp"
#include "anascan/processing/surface/model_report.hpp"
#include "anascan/processing/surface/reconstruction.hpp"

namespace {

using anascan::Mesh;
using anascan::PointCloud;

struct Args {
    std::string conf, reference;
    double resolution_mm = 0.5;
    Eigen::Vector3d sensor_scan_m{0.0, 0.0, 1.0};
    bool reference_samples = false, skip_open3d = false;
    anascan::SurfaceConfig config;  ///< Ours; the resolution is set from resolution_mm.
};

struct Scans {
    std::vector<PointCloud> clouds;  // world frame
    std::vector<Eigen::Vector3d> sensors_world_m;
    PointCloud all;
};

// Processor time of the process so far (all threads, user + system), seconds: on a loaded
// machine the wall time of each path depends on the other users, this does much less.
double cpu_seconds() {
    rusage u{};
    getrusage(RUSAGE_SELF, &u);
    return double(u.ru_utime.tv_sec + u.ru_stime.tv_sec) +
           1e-6 * double(u.ru_utime.tv_usec + u.ru_stime.tv_usec);
}

double peak_mb() {
    rusage u{};
    getrusage(RUSAGE_SELF, &u);
    return double(u.ru_maxrss) / 1024.0;
}

[[noreturn]] void die(const std::string& message) {
    std::fprintf(stderr, "bench_surface: %s\n", message.c_str());
    std::exit(1);
}

Scans load(const Args& a) {
    auto conf = anascan::io::read_conf(a.conf);
    if (!conf) die(conf.error().message);
    Scans s;
    const std::filesystem::path dir = std::filesystem::path(a.conf).parent_path();
    for (const auto& e : conf->entries) {
        auto mesh = anascan::io::read_mesh(dir / e.file);
        if (!mesh) die(mesh.error().message);
        remove_non_finite(mesh->vertices);
        s.clouds.push_back(anascan::transformed(mesh->vertices, e.T_world_scan));
        s.sensors_world_m.push_back(e.T_world_scan * a.sensor_scan_m);
        append(s.all, s.clouds.back());
    }
    return s;
}

struct Quality {
    double accuracy_median_mm = 0, accuracy_p95_mm = 0, completeness = 0;
    std::size_t accuracy_samples = 0;
};

double quantile(std::vector<double> v, double q) {
    if (v.empty()) return 0.0;
    const auto k = static_cast<std::ptrdiff_t>(q * double(v.size() - 1));
    std::nth_element(v.begin(), v.begin() + k, v.end());
    return v[std::size_t(k)];
}

Quality evaluate(const Mesh& mesh, const Mesh& reference, const Scans& scans, bool ref_samples) {
    Quality q;
    const anascan::KdTree scan_tree(scans.all.positions);
    const anascan::MeshDistance to_reference(reference);
    std::vector<double> d;
    for (const auto& s : anascan::sample_surface(mesh, 2e-4)) {
        anascan::Neighbor n;
        const Eigen::Vector3f local = (s.position_m - scans.all.origin_m).cast<float>();
        if (!scan_tree.nearest_within(local, 1e-3f, n)) continue;
        d.push_back(1e3 * to_reference.distance_m(s.position_m));
    }
    q.accuracy_samples = d.size();
    q.accuracy_median_mm = quantile(d, 0.5);
    q.accuracy_p95_mm = quantile(d, 0.95);
    const anascan::MeshDistance to_mesh(mesh);
    std::size_t near = 0, total = 0;
    const auto count = [&](const Eigen::Vector3d& p) {
        ++total;
        near += to_mesh.distance_m(p) <= 5e-4;
    };
    if (ref_samples) {
        for (const auto& s : anascan::sample_surface(reference, 5e-4)) count(s.position_m);
    } else {
        for (std::size_t i = 0; i < reference.vertices.size(); ++i) {
            count(reference.vertices.world_position(i));
        }
    }
    q.completeness = total ? double(near) / double(total) : 0.0;
    return q;
}

Mesh open3d_path(const Scans& scans) {
    open3d::geometry::PointCloud merged;
    for (std::size_t i = 0; i < scans.clouds.size(); ++i) {
        open3d::geometry::PointCloud pcd;
        for (std::size_t k = 0; k < scans.clouds[i].size(); ++k) {
            pcd.points_.push_back(scans.clouds[i].world_position(k));
        }
        pcd.EstimateNormals(open3d::geometry::KDTreeSearchParamKNN(20));
        pcd.OrientNormalsTowardsCameraLocation(scans.sensors_world_m[i]);
        merged += pcd;
    }
    auto [o3d, density] = open3d::geometry::TriangleMesh::CreateFromPointCloudPoisson(merged, 10);
    const double cut = quantile(density, 0.01);
    std::vector<bool> remove(density.size());
    for (std::size_t v = 0; v < density.size(); ++v) remove[v] = density[v] < cut;
    o3d->RemoveVerticesByMask(remove);
    Mesh mesh;
    for (const auto& v : o3d->vertices_) mesh.vertices.positions.push_back(v.cast<float>());
    mesh.triangles.assign(o3d->triangles_.begin(), o3d->triangles_.end());
    return mesh;
}

void print_quality(const char* who, double seconds, double cpu, const Quality& q) {
    std::printf(
        "%-8s %9.2f s wall %9.2f s cpu  accuracy median %.4f mm  p95 %.4f mm (%zu samples)  "
        "completeness %.2f%% within 0.5 mm\n",
        who, seconds, cpu, q.accuracy_median_mm, q.accuracy_p95_mm, q.accuracy_samples,
        100.0 * q.completeness);
}

Args parse(int argc, char** argv) {
    Args a;
    std::vector<std::string> pos;
    for (int i = 1; i < argc; ++i) {
        const std::string s = argv[i];
        if (s == "--resolution-mm" && i + 1 < argc) {
            a.resolution_mm = std::atof(argv[++i]);
        } else if (s == "--sensor" && i + 3 < argc) {
            for (int k = 0; k < 3; ++k) a.sensor_scan_m[k] = std::atof(argv[++i]);
        } else if (s == "--poisson-sample-cells" && i + 1 < argc) {
            a.config.poisson_sample_cells = std::atof(argv[++i]);
        } else if (s == "--poisson-scale" && i + 1 < argc) {
            a.config.poisson_scale = std::atof(argv[++i]);
        } else if (s == "--poisson-threads" && i + 1 < argc) {
            a.config.poisson_threads = std::atoi(argv[++i]);
        } else if (s == "--max-memory-mb" && i + 1 < argc) {
            a.config.max_memory_bytes = std::size_t(std::atof(argv[++i]) * 1048576.0);
        } else if (s == "--octree-cell-factor" && i + 1 < argc) {
            a.config.octree_cell_factor = std::atof(argv[++i]);
        } else if (s == "--no-fit-to-points") {
            a.config.fit_to_points = false;
        } else if (s == "--linear-fit") {
            a.config.poisson_linear_fit = true;
        } else if (s == "--reference-samples") {
            a.reference_samples = true;
        } else if (s == "--skip-open3d") {
            a.skip_open3d = true;
        } else {
            pos.push_back(s);
        }
    }
    if (pos.size() != 2) die("usage: anascan_bench_surface POSES.conf REFERENCE.ply [options]");
    a.conf = pos[0];
    a.reference = pos[1];
    return a;
}

/// The reference mesh's own report: whether it is closed, its volume and box.
void print_reference(const Mesh& reference) {
    const auto ref_report = anascan::make_model_report(
        {.mesh = reference,
         .support_distance_m = std::vector<float>(reference.vertices.size()),
         .support_scans = std::vector<std::uint16_t>(reference.vertices.size()),
         .vertex_class = std::vector(reference.vertices.size(), anascan::SurfaceClass::kMeasured),
         .triangle_class =
             std::vector(reference.triangles.size(), anascan::SurfaceClass::kMeasured)},
        {});
    std::printf("reference: closed %d, volume %.9f m^3, box %.2f x %.2f x %.2f mm\n",
                ref_report.closed, ref_report.volume_m3, ref_report.obb_mm.x(),
                ref_report.obb_mm.y(), ref_report.obb_mm.z());
}

}  // namespace

int main(int argc, char** argv) {
    const Args a = parse(argc, argv);
    const Scans scans = load(a);
    auto reference = anascan::io::read_mesh(a.reference);
    if (!reference) die(reference.error().message);
    std::printf("%zu scans, %zu points; reference %zu vertices; resolution %.2f mm\n",
                scans.clouds.size(), scans.all.size(), reference->vertices.size(), a.resolution_mm);
    const double load_mb = peak_mb();
    std::vector<anascan::PlacedScan> placed;
    for (std::size_t i = 0; i < scans.clouds.size(); ++i) {
        placed.push_back({&scans.clouds[i], scans.sensors_world_m[i]});
    }
    anascan::Stopwatch watch;
    double cpu = cpu_seconds();
    anascan::SurfaceConfig config = a.config;
    config.resolution_m = a.resolution_mm * 1e-3;
    const auto ours = anascan::reconstruct_surface(placed, config);
    const auto report = anascan::make_model_report(ours.model, ours.merged);
    const double t_ours = watch.lap(), cpu_ours = cpu_seconds() - cpu;
    const auto& dg = ours.diagnostics;
    std::printf(
        "ours: stages merge %.2f s, normals %.2f s, poisson %.2f s, support %.2f s; "
        "%zu merged points (%zu to Poisson), spacing %.3f mm\n",
        dg.seconds_merge, dg.seconds_normals, dg.seconds_poisson, dg.seconds_support,
        dg.merged_points, dg.poisson_samples, 1e3 * dg.spacing_m);
    std::printf(
        "ours: status %s, depth %d, %zu triangles, peak memory %.0f MB (%.0f MB after "
        "loading)\n%s",
        std::string(to_string(ours.status)).c_str(), ours.diagnostics.poisson_depth,
        ours.model.mesh.triangles.size(), peak_mb(), load_mb,
        anascan::model_report_table(report).c_str());
    print_reference(*reference);
    print_quality("ours", t_ours, cpu_ours,
                  evaluate(ours.model.mesh, *reference, scans, a.reference_samples));
    if (a.skip_open3d) return 0;
    watch.restart();
    cpu = cpu_seconds();
    const Mesh peer = open3d_path(scans);
    const double t_peer = watch.lap(), cpu_peer = cpu_seconds() - cpu;
    print_quality("open3d", t_peer, cpu_peer,
                  evaluate(peer, *reference, scans, a.reference_samples));
    std::printf("time ratio open3d / ours: %.2f wall, %.2f cpu\n", t_peer / t_ours,
                cpu_peer / cpu_ours);
    return 0;
}
