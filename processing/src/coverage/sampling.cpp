// Coverage, surface samples: area-weighted random points on a mesh with triangle normals.
// Each triangle gets area / spacing² samples, the fraction rounded at random (fixed seed),
// so every sample stands for the same area on average and the covered fraction is an
// unbiased area estimate.

#include <cstdint>

#include "coverage/steps.hpp"

namespace anascan::coverage_detail {
namespace {

// SplitMix64: a small, fully specified generator (same numbers on every platform).
struct SplitMix64 {
    std::uint64_t state;
    std::uint64_t next() {
        std::uint64_t z = (state += 0x9e3779b97f4a7c15ULL);
        z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9ULL;
        z = (z ^ (z >> 27)) * 0x94d049bb133111ebULL;
        return z ^ (z >> 31);
    }
    double uniform() { return static_cast<double>(next() >> 11) * 0x1.0p-53; }
};

}  // namespace

SurfaceSamples sample_surface(const Mesh& mesh, double spacing_m, std::uint64_t seed) {
    SurfaceSamples out;
    SplitMix64 rng{seed};
    const double per_m2 = 1.0 / (spacing_m * spacing_m);
    const auto& v = mesh.vertices.positions;
    for (const Eigen::Vector3i& t : mesh.triangles) {
        const Eigen::Vector3d a = v[t[0]].cast<double>();
        const Eigen::Vector3d ab = v[t[1]].cast<double>() - a;
        const Eigen::Vector3d ac = v[t[2]].cast<double>() - a;
        const Eigen::Vector3d cross = ab.cross(ac);
        const double area = 0.5 * cross.norm();
        if (!(area > 0.0)) continue;
        out.surface_area_m2 += area;
        const double expected = area * per_m2;
        auto count = static_cast<std::int64_t>(expected);
        if (rng.uniform() < expected - static_cast<double>(count)) ++count;
        const Eigen::Vector3f normal = cross.normalized().cast<float>();
        for (std::int64_t i = 0; i < count; ++i) {
            double s = rng.uniform(), r = rng.uniform();
            if (s + r > 1.0) s = 1.0 - s, r = 1.0 - r;
            out.positions.push_back((a + s * ab + r * ac).cast<float>());
            out.normals.push_back(normal);
        }
    }
    return out;
}

}  // namespace anascan::coverage_detail
