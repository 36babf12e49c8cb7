#include "anascan/processing/surface/mesh_distance.hpp"

#include <Eigen/Geometry>
#include <cmath>
#include <limits>
#include <random>

namespace anascan {

MeshDistance::MeshDistance(const Mesh& mesh)
    : origin_m_(mesh.vertices.origin_m), tree_(mesh.vertices.positions, mesh.triangles) {}

double MeshDistance::distance_m(const Eigen::Vector3d& point_world_m) const {
    double d = std::numeric_limits<double>::infinity();
    std::size_t triangle = 0;
    closest(point_world_m, d, triangle);
    return d;
}

bool MeshDistance::closest(const Eigen::Vector3d& point_world_m, double& distance_m,
                           std::size_t& triangle) const {
    const Eigen::Vector3d q = point_world_m - origin_m_;
    Eigen::Vector3d on;
    if (!tree_.closest(q, on, triangle)) return false;
    distance_m = (q - on).norm();
    return true;
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

}  // namespace anascan
