// Coverage, holes: the samples not observed, linked when closer than twice the sample
// spacing (random samples leave gaps up to about that) and their normals differ by less
// than 45° (so a hole does not turn a sharp edge: each missing face is its own hole),
// grouped into connected regions.

#include <algorithm>

#include "anascan/processing/spatial/kdtree.hpp"
#include "coverage/steps.hpp"

namespace anascan::coverage_detail {
namespace {

// Breadth-first search from `seed` over unvisited points; returns the region's indices.
constexpr float kMinNormalCos = 0.7071f;  // 45°

std::vector<std::size_t> grow_region(const KdTree& tree, std::span<const Eigen::Vector3f> points,
                                     std::span<const Eigen::Vector3f> normals, std::size_t seed,
                                     float link_m, std::vector<bool>& visited) {
    std::vector<std::size_t> region{seed};
    visited[seed] = true;
    std::vector<Neighbor> neighbors;
    for (std::size_t k = 0; k < region.size(); ++k) {
        tree.radius_any_order(points[region[k]], link_m, neighbors);
        for (const Neighbor& nb : neighbors) {
            if (visited[nb.index] || normals[nb.index].dot(normals[region[k]]) < kMinNormalCos)
                continue;
            visited[nb.index] = true;
            region.push_back(nb.index);
        }
    }
    return region;
}

CoverageHole describe_hole(std::span<const Eigen::Vector3f> positions,
                           std::span<const Eigen::Vector3f> normals,
                           std::span<const std::size_t> region, double area_per_sample_m2,
                           const Eigen::Vector3d& origin_m) {
    CoverageHole hole;
    Eigen::Vector3d sum_p = Eigen::Vector3d::Zero(), sum_n = Eigen::Vector3d::Zero();
    for (std::size_t i : region) {
        sum_p += positions[i].cast<double>();
        sum_n += normals[i].cast<double>();
    }
    hole.sample_count = region.size();
    hole.area_m2 = static_cast<double>(region.size()) * area_per_sample_m2;
    hole.centre_m = origin_m + sum_p / static_cast<double>(region.size());
    if (sum_n.norm() > 0.0) hole.normal = sum_n.normalized();
    return hole;
}

}  // namespace

std::vector<CoverageHole> find_holes(const SurfaceSamples& samples,
                                     std::span<const SampleState> states,
                                     const Eigen::Vector3d& origin_m,
                                     const CoverageConfig& config) {
    std::vector<Eigen::Vector3f> positions, normals;
    for (std::size_t i = 0; i < states.size(); ++i) {
        if (states[i] == SampleState::kObserved) continue;
        positions.push_back(samples.positions[i]);
        normals.push_back(samples.normals[i]);
    }
    std::vector<CoverageHole> holes;
    if (positions.empty()) return holes;
    const double area_per_sample =
        samples.surface_area_m2 / static_cast<double>(samples.positions.size());
    const KdTree tree(positions);
    const auto link_m = static_cast<float>(2.0 * config.sample_spacing_m);
    std::vector<bool> visited(positions.size(), false);
    for (std::size_t seed = 0; seed < positions.size(); ++seed) {
        if (visited[seed]) continue;
        const std::vector<std::size_t> region =
            grow_region(tree, positions, normals, seed, link_m, visited);
        CoverageHole hole = describe_hole(positions, normals, region, area_per_sample, origin_m);
        if (hole.area_m2 >= config.min_hole_area_m2) holes.push_back(hole);
    }
    std::stable_sort(holes.begin(), holes.end(),
                     [](const auto& a, const auto& b) { return a.area_m2 > b.area_m2; });
    return holes;
}

}  // namespace anascan::coverage_detail
