#include "fit_to_points.hpp"

#include <tbb/parallel_for.h>

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <optional>
#include <vector>

namespace anascan::surface_detail {
namespace {

// Normals within this angle of the nearest point's belong to the same face: across an arris
// of a dressed block the faces meet at 60-120°, while the normals of one face, estimated
// on 15 neighbours, scatter by a few degrees.
const float kSameFaceCos = std::cos(30.0f * 3.14159265f / 180.0f);
constexpr int kMinSupport = 3;

struct LocalPlane {
    Eigen::Vector3f point;
    Eigen::Vector3f normal;
};

// The plane of the points around the nearest point p0 (not around q, which may lie a cell
// off the surface: a neighbourhood centred on p0 is symmetric on the surface, so curvature
// biases the plane by only about curvature x sigma^2 / 2).
std::optional<LocalPlane> local_plane(const PointCloud& merged, const KdTree& tree,
                                      const Eigen::Vector3f& q, float reach_m, float sigma_m,
                                      std::vector<Neighbor>& near) {
    Neighbor nn;
    if (!tree.nearest_within(q, reach_m, nn)) return std::nullopt;
    const Eigen::Vector3f p0 = merged.positions[nn.index];
    const Eigen::Vector3f n0 = merged.normals[nn.index];
    if (!(n0.squaredNorm() > 0.0f)) return std::nullopt;
    tree.radius_any_order(p0, 2.0f * sigma_m, near);
    const float inv_two_sigma_sq = 0.5f / (sigma_m * sigma_m);
    Eigen::Vector3f centre = Eigen::Vector3f::Zero(), normal = Eigen::Vector3f::Zero();
    float weight = 0.0f;
    int support = 0;
    for (const Neighbor& p : near) {
        const Eigen::Vector3f& n = merged.normals[p.index];
        if (n.dot(n0) < kSameFaceCos) continue;
        const float w = std::exp(-p.distance_sq_m2 * inv_two_sigma_sq);
        centre += w * merged.positions[p.index];
        normal += w * n;
        weight += w;
        ++support;
    }
    if (support < kMinSupport || !(normal.squaredNorm() > 0.0f)) return std::nullopt;
    return LocalPlane{centre / weight, normal.normalized()};
}

// Area-weighted vertex normals (triangles counter-clockwise seen from outside), as Poisson's
// mesh had them before its vertices moved.
void recompute_vertex_normals(Mesh& mesh) {
    const auto& p = mesh.vertices.positions;
    std::vector<Eigen::Vector3f> sums(p.size(), Eigen::Vector3f::Zero());
    for (const Eigen::Vector3i& t : mesh.triangles) {
        const Eigen::Vector3f area_normal = (p[t[1]] - p[t[0]]).cross(p[t[2]] - p[t[0]]);
        for (int k = 0; k < 3; ++k) sums[t[k]] += area_normal;
    }
    for (Eigen::Vector3f& s : sums)
        if (s.squaredNorm() > 0.0f) s.normalize();
    mesh.vertices.normals = std::move(sums);
}

}  // namespace

PointFitStats fit_vertices_to_points(Mesh& mesh, const PointCloud& merged, const KdTree& tree,
                                     double reach_m, double sigma_m) {
    PointCloud& v = mesh.vertices;
    const std::size_t n = v.size();
    if (n == 0 || merged.empty() || merged.normals.size() != merged.size()) return {};
    const Eigen::Vector3f shift = (v.origin_m - merged.origin_m).cast<float>();
    const float reach = static_cast<float>(reach_m), sigma = static_cast<float>(sigma_m);
    std::vector<float> moved_by(n, -1.0f);
    tbb::parallel_for(tbb::blocked_range<std::size_t>(0, n, 1024), [&](const auto& range) {
        std::vector<Neighbor> near;
        for (std::size_t i = range.begin(); i != range.end(); ++i) {
            const Eigen::Vector3f q = v.positions[i] + shift;
            const auto plane = local_plane(merged, tree, q, reach, sigma, near);
            if (!plane) continue;
            const float offset = (q - plane->point).dot(plane->normal);
            if (!(std::abs(offset) <= reach)) continue;
            v.positions[i] -= offset * plane->normal;
            moved_by[i] = std::abs(offset);
        }
    });
    recompute_vertex_normals(mesh);
    std::vector<float> shifts;
    for (float s : moved_by)
        if (s >= 0.0f) shifts.push_back(s);
    PointFitStats stats;
    stats.moved = shifts.size();
    if (!shifts.empty()) {
        auto mid = shifts.begin() + std::ptrdiff_t(shifts.size() / 2);
        std::nth_element(shifts.begin(), mid, shifts.end());
        stats.median_shift_m = *mid;
    }
    return stats;
}

}  // namespace anascan::surface_detail
