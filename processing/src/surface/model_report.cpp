#include "anascan/processing/surface/model_report.hpp"

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <cstdio>

#include "anascan/processing/spatial/kdtree.hpp"
#include "anascan/processing/surface/mesh_topology.hpp"

namespace anascan {
namespace {

HoleReport describe_hole(const PointCloud& v, const std::vector<int>& loop) {
    HoleReport h;
    h.outline_vertices = loop.size();
    for (const int i : loop) {
        h.outline_m.push_back(v.world_position(i));
        h.centroid_m += h.outline_m.back();
    }
    h.centroid_m /= double(std::max<std::size_t>(1, loop.size()));
    for (std::size_t i = 0; i < loop.size(); ++i) {
        const Eigen::Vector3d& a = h.outline_m[i];
        const Eigen::Vector3d& b = h.outline_m[(i + 1) % loop.size()];
        h.perimeter_m += (b - a).norm();
        h.area_m2 += 0.5 * (a - h.centroid_m).cross(b - h.centroid_m).norm();
    }
    return h;
}

std::vector<HoleReport> measured_holes(const FragmentModel& model) {
    std::vector<bool> keep(model.mesh.triangles.size());
    for (std::size_t t = 0; t < keep.size(); ++t) {
        keep[t] = model.triangle_class[t] == SurfaceClass::kMeasured;
    }
    const FragmentModel measured = select_triangles(model, keep);
    const MeshTopology topo = analyse_topology(measured.mesh);
    std::vector<HoleReport> holes;
    for (const std::vector<int>& loop : topo.boundary_loops) {
        holes.push_back(describe_hole(measured.mesh.vertices, loop));
    }
    std::sort(holes.begin(), holes.end(),
              [](const HoleReport& a, const HoleReport& b) { return a.area_m2 > b.area_m2; });
    return holes;
}

double interpolated_share(const FragmentModel& model, double total_area) {
    if (total_area <= 0.0) return 0.0;
    Mesh part;
    part.vertices.positions = model.mesh.vertices.positions;
    for (std::size_t t = 0; t < model.mesh.triangles.size(); ++t) {
        if (model.triangle_class[t] == SurfaceClass::kInterpolated) {
            part.triangles.push_back(model.mesh.triangles[t]);
        }
    }
    return mesh_area_m2(part) / total_area;
}

double quantile(std::vector<double>& values, double q) {
    if (values.empty()) return 0.0;
    const auto k = static_cast<std::ptrdiff_t>(q * double(values.size() - 1));
    std::nth_element(values.begin(), values.begin() + k, values.end());
    return values[static_cast<std::size_t>(k)];
}

void measure_accuracy(const FragmentModel& model, const PointCloud& merged, ModelReport& r) {
    if (merged.empty() || !merged.has_normals()) return;
    const KdTree tree(merged.positions);
    const PointCloud& v = model.mesh.vertices;
    const Eigen::Vector3f shift = (v.origin_m - merged.origin_m).cast<float>();
    std::vector<double> d;
    for (std::size_t i = 0; i < v.size(); ++i) {
        if (model.vertex_class[i] != SurfaceClass::kMeasured) continue;
        const Eigen::Vector3f q = v.positions[i] + shift;
        Neighbor nn;
        if (!tree.nearest(q, nn)) continue;
        const Eigen::Vector3f& n = merged.normals[nn.index];
        const Eigen::Vector3f dq = q - merged.positions[nn.index];
        d.push_back(n.squaredNorm() > 0 ? std::abs(double(n.dot(dq))) : double(dq.norm()));
    }
    r.accuracy_samples = d.size();
    r.accuracy_median_m = quantile(d, 0.5);
    r.accuracy_p95_m = quantile(d, 0.95);
}

}  // namespace

ModelReport make_model_report(const FragmentModel& model, const PointCloud& merged) {
    ModelReport r;
    r.vertices = model.mesh.vertices.size();
    r.triangles = model.mesh.triangles.size();
    const MeshTopology topo = analyse_topology(model.mesh);
    r.closed = topo.closed();
    r.manifold = topo.manifold();
    r.components = topo.components;
    r.area_m2 = mesh_area_m2(model.mesh);
    r.volume_m3 = mesh_volume_m3(model.mesh);
    r.obb_mm = oriented_box_mm(model.mesh);
    r.interpolated_area_share = interpolated_share(model, r.area_m2);
    r.holes = measured_holes(model);
    measure_accuracy(model, merged, r);
    return r;
}

std::string model_report_table(const ModelReport& r) {
    char text[1024];
    std::snprintf(text, sizeof(text),
                  "vertices %zu, triangles %zu\n"
                  "closed %s, manifold %s, components %zu\n"
                  "area %.6f m^2, volume %.9f m^3\n"
                  "oriented box %.1f x %.1f x %.1f mm\n"
                  "interpolated %.2f%% of the area; %zu holes in the measured surface%s\n"
                  "accuracy against the scans: median %.3f mm, p95 %.3f mm (%zu vertices)\n",
                  r.vertices, r.triangles, r.closed ? "yes" : "no", r.manifold ? "yes" : "no",
                  r.components, r.area_m2, r.volume_m3, r.obb_mm.x(), r.obb_mm.y(), r.obb_mm.z(),
                  100.0 * r.interpolated_area_share, r.holes.size(),
                  r.holes.empty() ? "" : " (largest listed below)", 1e3 * r.accuracy_median_m,
                  1e3 * r.accuracy_p95_m, r.accuracy_samples);
    std::string out = text;
    for (std::size_t i = 0; i < std::min<std::size_t>(5, r.holes.size()); ++i) {
        const HoleReport& h = r.holes[i];
        std::snprintf(text, sizeof(text),
                      "  hole %zu: %.1f mm^2, outline %.1f mm (%zu vertices) at %.4f %.4f %.4f m\n",
                      i + 1, 1e6 * h.area_m2, 1e3 * h.perimeter_m, h.outline_vertices,
                      h.centroid_m.x(), h.centroid_m.y(), h.centroid_m.z());
        out += text;
    }
    return out;
}

}  // namespace anascan
