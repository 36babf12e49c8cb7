#include "poisson.hpp"

#include <open3d/geometry/PointCloud.h>
#include <open3d/geometry/TriangleMesh.h>

#include <algorithm>
#include <cmath>

namespace anascan::surface_detail {
namespace {

// Memory of Open3D's Poisson: a part per sample and a part per surface cell of the finest
// level (about one per merged sample when the cell equals the resolution, fewer when it is
// coarser). The bunny at 0.5 mm (235,064 samples, depth 9) estimates 705 MB for a measured
// peak of 531 MB (docs/surface-reconstruction.md): a bound, not a prediction.
constexpr double kBytesPerPoint = 100.0, kBytesPerCell = 1300.0;
constexpr int kMinDepth = 5, kMaxDepth = 12;

}  // namespace

PoissonDepth choose_depth(double box_m, double finest_cell_m, double resolution_m,
                          std::size_t points, std::size_t max_memory_bytes) {
    PoissonDepth d;
    d.depth = std::clamp(static_cast<int>(std::ceil(std::log2(box_m / finest_cell_m))), kMinDepth,
                         kMaxDepth);
    for (;; --d.depth) {
        d.cell_m = box_m / std::ldexp(1.0, d.depth);
        const double cells_per_sample = std::pow(resolution_m / d.cell_m, 2.0);
        d.estimated_memory_bytes = static_cast<std::size_t>(
            double(points) * (kBytesPerPoint + kBytesPerCell * cells_per_sample));
        if (d.estimated_memory_bytes <= max_memory_bytes || d.depth == kMinDepth) break;
    }
    return d;
}

Mesh poisson_surface(const PointCloud& cloud, const PoissonParams& params) {
    open3d::geometry::PointCloud pcd;
    pcd.points_.reserve(cloud.size());
    pcd.normals_.reserve(cloud.size());
    for (std::size_t i = 0; i < cloud.size(); ++i) {
        if (!(cloud.normals[i].squaredNorm() > 0.0f)) continue;  // no normal (or NaN): no sample
        pcd.points_.push_back(cloud.positions[i].cast<double>());
        pcd.normals_.push_back(cloud.normals[i].cast<double>());
    }
    Mesh mesh;
    mesh.vertices.origin_m = cloud.origin_m;
    if (pcd.points_.size() < 4) return mesh;
    auto [o3d, densities] = open3d::geometry::TriangleMesh::CreateFromPointCloudPoisson(
        pcd, static_cast<std::size_t>(params.depth), 0.0f, static_cast<float>(params.scale),
        params.linear_fit, params.threads);
    if (!o3d || o3d->triangles_.empty()) return mesh;
    o3d->ComputeVertexNormals();
    mesh.vertices.positions.reserve(o3d->vertices_.size());
    for (const Eigen::Vector3d& v : o3d->vertices_)
        mesh.vertices.positions.push_back(v.cast<float>());
    for (const Eigen::Vector3d& n : o3d->vertex_normals_)
        mesh.vertices.normals.push_back(n.cast<float>());
    mesh.triangles.assign(o3d->triangles_.begin(), o3d->triangles_.end());
    return mesh;
}

}  // namespace anascan::surface_detail
