// Signed distance by angle-weighted pseudo-normals (see mesh_distance.hpp).
#include "mesh_distance.hpp"

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>

namespace anascan::reassembly::detail {
namespace {

std::uint64_t edge_key(int a, int b) {
    return (std::uint64_t(std::uint32_t(std::min(a, b))) << 32) |
           std::uint64_t(std::uint32_t(std::max(a, b)));
}

Eigen::Vector3d at(std::span<const Eigen::Vector3f> v, int i) {
    return v[std::size_t(i)].cast<double>();
}

double corner_angle(const Eigen::Vector3d& p, const Eigen::Vector3d& a, const Eigen::Vector3d& b) {
    const Eigen::Vector3d u = a - p, w = b - p;
    return std::atan2(u.cross(w).norm(), u.dot(w));
}

// Barycentric coordinates of q (in the triangle's plane) in triangle a, b, c.
Eigen::Vector3d barycentric(const Eigen::Vector3d& q, const Eigen::Vector3d& a,
                            const Eigen::Vector3d& b, const Eigen::Vector3d& c) {
    const Eigen::Vector3d n = (b - a).cross(c - a);
    const double area2 = n.squaredNorm();
    const double wa = (c - b).cross(q - b).dot(n) / area2;
    const double wb = (a - c).cross(q - c).dot(n) / area2;
    return {wa, wb, 1.0 - wa - wb};
}

}  // namespace

MeshDistance::MeshDistance(std::span<const Eigen::Vector3f> vertices,
                           std::span<const Eigen::Vector3i> triangles)
    : vertices_(vertices),
      triangles_(triangles),
      face_normal_(triangles.size(), Eigen::Vector3d::Zero()),
      vertex_normal_(vertices.size(), Eigen::Vector3d::Zero()),
      vertex_boundary_(vertices.size(), 0),
      edge_normal_(3 * triangles.size(), Eigen::Vector3d::Zero()),
      edge_boundary_(3 * triangles.size(), 0),
      tree_(vertices, triangles) {
    std::vector<std::pair<std::uint64_t, std::size_t>> edges;  // (key, 3 t + k)
    edges.reserve(3 * triangles.size());
    for (std::size_t t = 0; t < triangles.size(); ++t) {
        const Eigen::Vector3i& f = triangles[t];
        const Eigen::Vector3d n = (at(vertices, f[1]) - at(vertices, f[0]))
                                      .cross(at(vertices, f[2]) - at(vertices, f[0]));
        if (n.norm() > 0.0) face_normal_[t] = n.normalized();
        for (int k = 0; k < 3; ++k) {
            const int p = f[k], a = f[(k + 1) % 3], b = f[(k + 2) % 3];
            vertex_normal_[std::size_t(p)] +=
                corner_angle(at(vertices, p), at(vertices, a), at(vertices, b)) * face_normal_[t];
            edges.emplace_back(edge_key(p, a), 3 * t + std::size_t(k));
        }
    }
    std::ranges::sort(edges);
    for (std::size_t i = 0, j = 0; i < edges.size(); i = j) {
        Eigen::Vector3d sum = Eigen::Vector3d::Zero();
        for (j = i; j < edges.size() && edges[j].first == edges[i].first; ++j)
            sum += face_normal_[edges[j].second / 3];
        const bool boundary = j - i != 2;  // One triangle: a hole's rim; three: non-manifold.
        for (std::size_t e = i; e < j; ++e)
            edge_normal_[edges[e].second] = sum, edge_boundary_[edges[e].second] = boundary;
        if (!boundary) continue;
        vertex_boundary_[std::size_t(edges[i].first >> 32)] = 1;
        vertex_boundary_[std::size_t(edges[i].first & 0xffffffffu)] = 1;
    }
}

bool MeshDistance::signed_distance(const Eigen::Vector3d& x, SignedDistance& out) const {
    Eigen::Vector3d q;
    std::size_t t = 0;
    if (!tree_.closest(x, q, t)) return false;
    const Eigen::Vector3i& f = triangles_[t];
    const Eigen::Vector3d w =
        barycentric(q, at(vertices_, f[0]), at(vertices_, f[1]), at(vertices_, f[2]));
    constexpr double kOnFeature = 1e-7;  // Barycentric rounding of the closest point.
    const int zeros = int(w[0] < kOnFeature) + int(w[1] < kOnFeature) + int(w[2] < kOnFeature);
    Eigen::Vector3d n = face_normal_[t];
    out.boundary = false;
    if (zeros >= 2) {  // At a vertex: the one with weight ~1.
        int k = 0;
        w.maxCoeff(&k);
        n = vertex_normal_[std::size_t(f[k])];
        out.boundary = vertex_boundary_[std::size_t(f[k])] != 0;
    } else if (zeros == 1) {  // On the edge opposite the zero weight.
        int k = 0;
        w.minCoeff(&k);
        const std::size_t e = 3 * t + std::size_t((k + 1) % 3);  // Corner k+1 to k+2.
        n = edge_normal_[e];
        out.boundary = edge_boundary_[e] != 0;
    }
    const double d = (x - q).norm();
    out.distance_m = (x - q).dot(n) < 0.0 ? -d : d;
    return true;
}

}  // namespace anascan::reassembly::detail
