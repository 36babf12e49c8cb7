// Open3D's screened Poisson (a port of Kazhdan's PoissonRecon), built as a module that
// poisson.cpp loads on first use. Linked into the processing library, Open3D and the 48
// libraries only it brings were loaded by every program at start: 65 ms of each command
// (docs/surface-reconstruction.md, "Open3D as a module"). The only file that includes Open3D.
#include <open3d/geometry/PointCloud.h>
#include <open3d/geometry/TriangleMesh.h>

#include "poisson.hpp"

namespace {

using anascan::Mesh;
using anascan::PointCloud;
using anascan::surface_detail::PoissonParams;

void run_poisson(const PointCloud& cloud, const PoissonParams& params, Mesh& mesh) {
    open3d::geometry::PointCloud pcd;
    pcd.points_.reserve(cloud.size());
    pcd.normals_.reserve(cloud.size());
    for (std::size_t i = 0; i < cloud.size(); ++i) {
        if (!(cloud.normals[i].squaredNorm() > 0.0f)) continue;  // no normal (or NaN): no sample
        pcd.points_.push_back(cloud.positions[i].cast<double>());
        pcd.normals_.push_back(cloud.normals[i].cast<double>());
    }
    mesh = Mesh{};
    mesh.vertices.origin_m = cloud.origin_m;
    if (pcd.points_.size() < 4) return;
    auto [o3d, densities] = open3d::geometry::TriangleMesh::CreateFromPointCloudPoisson(
        pcd, static_cast<std::size_t>(params.depth), 0.0f, static_cast<float>(params.scale),
        params.linear_fit, params.threads);
    if (!o3d || o3d->triangles_.empty()) return;
    o3d->ComputeVertexNormals();
    mesh.vertices.positions.reserve(o3d->vertices_.size());
    for (const Eigen::Vector3d& v : o3d->vertices_)
        mesh.vertices.positions.push_back(v.cast<float>());
    for (const Eigen::Vector3d& n : o3d->vertex_normals_)
        mesh.vertices.normals.push_back(n.cast<float>());
    mesh.triangles.assign(o3d->triangles_.begin(), o3d->triangles_.end());
}

}  // namespace

/// The module's one entry; poisson.cpp finds it by this name. `mesh` is emptied, then
/// receives the surface in the cloud's frame with vertex normals (empty on failure).
extern "C" __attribute__((visibility("default"))) void anascan_poisson_surface_v1(
    const PointCloud& cloud, const PoissonParams& params, Mesh& mesh) {
    run_poisson(cloud, params, mesh);
}
