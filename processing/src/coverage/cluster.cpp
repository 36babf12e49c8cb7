// Coverage, background removal: the stone is the connected cluster of occupied voxels
// nearest the median of the points off the ground (the median ignores a far tent wall).

#include <algorithm>
#include <cmath>
#include <limits>
#include <unordered_map>

#include "coverage/steps.hpp"

namespace anascan::coverage_detail {
namespace {

using Cell = Eigen::Vector3i;

struct Voxel {
    Cell cell;
    double weight = 0.0;
    int component = -1;
};

struct Occupancy {
    std::vector<Voxel> voxels;
    std::unordered_map<std::uint64_t, std::size_t> index;
    std::vector<std::size_t> voxel_of;  // per candidate
};

Occupancy occupy(const BinnedPoints& points, std::span<const std::size_t> candidates,
                 double voxel_m) {
    Occupancy occ;
    occ.voxel_of.reserve(candidates.size());
    for (std::size_t i : candidates) {
        const Cell cell =
            (points.positions[i] / static_cast<float>(voxel_m)).array().floor().cast<int>();
        auto [it, inserted] = occ.index.try_emplace(pack_cell(cell), occ.voxels.size());
        if (inserted) occ.voxels.push_back(Voxel{.cell = cell});
        occ.voxels[it->second].weight += points.weights[i];
        occ.voxel_of.push_back(it->second);
    }
    return occ;
}

// Labels the 26-connected components of the voxels heavy enough; returns their count.
int label_components(Occupancy& occ, double min_weight) {
    int components = 0;
    std::vector<std::size_t> stack;
    for (std::size_t seed = 0; seed < occ.voxels.size(); ++seed) {
        if (occ.voxels[seed].component >= 0 || occ.voxels[seed].weight < min_weight) continue;
        occ.voxels[seed].component = components;
        stack.assign(1, seed);
        while (!stack.empty()) {
            const Cell c = occ.voxels[stack.back()].cell;
            stack.pop_back();
            for (int d = 0; d < 27; ++d) {
                const Cell n = c + Cell(d % 3 - 1, d / 3 % 3 - 1, d / 9 - 1);
                auto it = occ.index.find(pack_cell(n));
                if (it == occ.index.end()) continue;
                Voxel& voxel = occ.voxels[it->second];
                if (voxel.component >= 0 || voxel.weight < min_weight) continue;
                voxel.component = components;
                stack.push_back(it->second);
            }
        }
        ++components;
    }
    return components;
}

Eigen::Vector3f median_point(const BinnedPoints& points, std::span<const std::size_t> candidates) {
    Eigen::Vector3f median;
    std::vector<float> values(candidates.size());
    for (int a = 0; a < 3; ++a) {
        for (std::size_t k = 0; k < candidates.size(); ++k)
            values[k] = points.positions[candidates[k]][a];
        std::nth_element(values.begin(),
                         values.begin() + static_cast<std::ptrdiff_t>(values.size() / 2),
                         values.end());
        median[a] = values[values.size() / 2];
    }
    return median;
}

}  // namespace

std::vector<std::size_t> nearest_cluster(const BinnedPoints& points,
                                         std::span<const std::size_t> candidates,
                                         const CoverageConfig& config) {
    if (candidates.empty()) return {};
    Occupancy occ = occupy(points, candidates, config.cluster_voxel_m);
    const int components = label_components(occ, config.min_cluster_voxel_points);
    if (components == 0) return {};
    const Eigen::Vector3f median = median_point(points, candidates);
    int best = -1;
    float best_distance = std::numeric_limits<float>::max();
    for (std::size_t k = 0; k < candidates.size(); ++k) {
        const int component = occ.voxels[occ.voxel_of[k]].component;
        if (component < 0) continue;
        const float distance = (points.positions[candidates[k]] - median).squaredNorm();
        if (distance < best_distance) best_distance = distance, best = component;
    }
    std::vector<std::size_t> stone;
    for (std::size_t k = 0; k < candidates.size(); ++k)
        if (occ.voxels[occ.voxel_of[k]].component == best) stone.push_back(candidates[k]);
    return stone;
}

}  // namespace anascan::coverage_detail
