#include "anascan/processing/surface/mesh_distance.hpp"

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <limits>
#include <random>

#include "anascan/processing/spatial/kdtree.hpp"

namespace anascan {

struct MeshDistance::Impl {
    const Mesh& mesh;
    int k = 8;
    KdTree tree;
    std::vector<std::uint32_t> first;  // CSR: triangles of vertex v are tris[first[v]..]
    std::vector<std::uint32_t> tris;

    Impl(const Mesh& m, int k_vertices) : mesh(m), k(k_vertices), tree(m.vertices.positions) {
        first.assign(m.vertices.size() + 1, 0);
        for (const Eigen::Vector3i& t : m.triangles) {
            for (int c = 0; c < 3; ++c) ++first[t[c] + 1];
        }
        for (std::size_t v = 0; v < m.vertices.size(); ++v) first[v + 1] += first[v];
        tris.resize(first.back());
        std::vector<std::uint32_t> fill(first.begin(), first.end() - 1);
        for (std::uint32_t i = 0; i < m.triangles.size(); ++i) {
            for (int c = 0; c < 3; ++c) tris[fill[m.triangles[i][c]]++] = i;
        }
    }
};

MeshDistance::MeshDistance(const Mesh& mesh, int k_vertices)
    : impl_(std::make_unique<Impl>(mesh, k_vertices)) {}
MeshDistance::~MeshDistance() = default;
MeshDistance::MeshDistance(MeshDistance&&) noexcept = default;
MeshDistance& MeshDistance::operator=(MeshDistance&&) noexcept = default;

double MeshDistance::distance_m(const Eigen::Vector3d& point_world_m) const {
    const Mesh& m = impl_->mesh;
    const Eigen::Vector3d q = point_world_m - m.vertices.origin_m;
    std::vector<Neighbor> near;
    impl_->tree.knn(q.cast<float>(), static_cast<std::size_t>(impl_->k), near);
    double best = std::numeric_limits<double>::infinity();
    for (const Neighbor& n : near) {
        for (std::uint32_t i = impl_->first[n.index]; i < impl_->first[n.index + 1]; ++i) {
            const Eigen::Vector3i& t = m.triangles[impl_->tris[i]];
            best =
                std::min(best, point_triangle_distance(q, m.vertices.positions[t[0]].cast<double>(),
                                                       m.vertices.positions[t[1]].cast<double>(),
                                                       m.vertices.positions[t[2]].cast<double>()));
        }
        if (impl_->first[n.index] == impl_->first[n.index + 1]) {
            best = std::min(best, std::sqrt(double(n.distance_sq_m2)));
        }
    }
    return best;
}

std::vector<SurfaceSample> sample_surface(const Mesh& mesh, double spacing_m, std::uint32_t seed) {
    std::mt19937 rng(seed);
    std::uniform_real_distribution<double> u(0.0, 1.0);
    std::vector<SurfaceSample> out;
    const auto& p = mesh.vertices.positions;
    const double per_area = 1.0 / (spacing_m * spacing_m);
    for (std::uint32_t t = 0; t < mesh.triangles.size(); ++t) {
        const Eigen::Vector3i& tri = mesh.triangles[t];
        const Eigen::Vector3d a = p[tri[0]].cast<double>(), b = p[tri[1]].cast<double>(),
                              c = p[tri[2]].cast<double>();
        const double expected = 0.5 * (b - a).cross(c - a).norm() * per_area;
        // Whole samples plus one more with the fractional part's probability.
        const auto count = static_cast<std::size_t>(expected + u(rng));
        for (std::size_t s = 0; s < count; ++s) {
            double r1 = u(rng), r2 = u(rng);
            if (r1 + r2 > 1.0) r1 = 1.0 - r1, r2 = 1.0 - r2;
            out.push_back({mesh.vertices.origin_m + a + r1 * (b - a) + r2 * (c - a), t});
        }
    }
    return out;
}

double point_triangle_distance(const Eigen::Vector3d& p, const Eigen::Vector3d& a,
                               const Eigen::Vector3d& b, const Eigen::Vector3d& c) {
    // Ericson, Real-Time Collision Detection §5.1.5: closest point by Voronoi regions.
    const Eigen::Vector3d ab = b - a, ac = c - a, ap = p - a;
    const double d1 = ab.dot(ap), d2 = ac.dot(ap);
    if (d1 <= 0 && d2 <= 0) return ap.norm();
    const Eigen::Vector3d bp = p - b;
    const double d3 = ab.dot(bp), d4 = ac.dot(bp);
    if (d3 >= 0 && d4 <= d3) return bp.norm();
    const double vc = d1 * d4 - d3 * d2;
    if (vc <= 0 && d1 >= 0 && d3 <= 0) return (p - (a + ab * (d1 / (d1 - d3)))).norm();
    const Eigen::Vector3d cp = p - c;
    const double d5 = ab.dot(cp), d6 = ac.dot(cp);
    if (d6 >= 0 && d5 <= d6) return cp.norm();
    const double vb = d5 * d2 - d1 * d6;
    if (vb <= 0 && d2 >= 0 && d6 <= 0) return (p - (a + ac * (d2 / (d2 - d6)))).norm();
    const double va = d3 * d6 - d5 * d4;
    if (va <= 0 && (d4 - d3) >= 0 && (d5 - d6) >= 0) {
        return (p - (b + (c - b) * ((d4 - d3) / ((d4 - d3) + (d5 - d6))))).norm();
    }
    const double denom = va + vb + vc;
    if (denom <= 0) return std::min({ap.norm(), bp.norm(), cp.norm()});  // degenerate
    const double v = vb / denom, w = vc / denom;
    return (p - (a + ab * v + ac * w)).norm();
}

}  // namespace anascan
