// Coverage, the stone's points without ground truth. Per view, the ground is the largest
// plane with (almost) nothing beyond it as seen from the sensor and the stone in front: a
// face of the stone has the ground or other faces behind it, the ground under a stone has
// nothing. A view aimed at the stone may show too little ground: it borrows a neighbour's. The
// points on the sensor's side of the ground (farther than ground_distance_m) are kept. Of those,
// the connected cluster of occupied voxels nearest the median point is the stone; the rest (tent,
// tools, neighbouring stones) is background.

#include <tbb/parallel_for.h>

#include <algorithm>
#include <optional>
#include <unordered_map>

#include "anascan/processing/cleaning/plane_removal.hpp"
#include "anascan/processing/spatial/voxel_grid.hpp"
#include "coverage/steps.hpp"

namespace anascan::coverage_detail {
namespace {

constexpr double kFitVoxelM = 0.012;          // plane fits on a coarse copy of the view
constexpr double kMaxBehindFraction = 0.02;   // of the view's points, beyond the ground
constexpr double kMinFrontFraction = 0.01;    // of the view's points, the stone in front
constexpr std::size_t kMinGroundPoints = 20;  // coarse points on the ground (~30 cm²)
constexpr int kMaxPlanes = 6;                 // candidate planes tried per view
constexpr double kHullVoxelM = 0.003;         // hull input thinned (centroids: <= 1.5 mm in)

PointCloud view_cloud(const BinnedPoints& points, std::size_t view) {
    PointCloud cloud;
    const auto [begin, end] = points.ranges[view];
    cloud.positions.assign(points.positions.begin() + static_cast<std::ptrdiff_t>(begin),
                           points.positions.begin() + static_cast<std::ptrdiff_t>(end));
    return cloud;
}

// Turns the plane's normal toward the sensor (when known; else it keeps the side of most
// points, as the plane fit returns it).
Plane facing_sensor(Plane plane, const Eigen::Vector3f& sensor) {
    if (sensor.allFinite() && plane.signed_distance_m(sensor) < 0.0) {
        plane.normal = -plane.normal;
        plane.offset_m = -plane.offset_m;
    }
    return plane;
}

// The ground of a view: enough points on it, (almost) none beyond it, some in front.
bool is_ground(const Plane& plane, const PointCloud& coarse, const CoverageConfig& config) {
    std::size_t on = 0, behind = 0, front = 0;
    for (const Eigen::Vector3f& p : coarse.positions) {
        const double d = plane.signed_distance_m(p);
        if (d < -2.0 * config.ground_distance_m)
            ++behind;
        else if (d > 2.0 * config.ground_distance_m)
            ++front;
        else
            ++on;
    }
    const auto n = static_cast<double>(coarse.size());
    return on >= kMinGroundPoints && static_cast<double>(behind) <= kMaxBehindFraction * n &&
           static_cast<double>(front) >= kMinFrontFraction * n;
}

std::optional<Plane> own_ground(const PointCloud& coarse, const Eigen::Vector3f& sensor,
                                const CoverageConfig& config) {
    PointCloud remaining = coarse;
    const PlaneFitConfig fit_config{.distance_threshold_m = config.ground_distance_m,
                                    .max_iterations = 200};
    for (int attempt = 0; attempt < kMaxPlanes && remaining.size() >= kMinGroundPoints; ++attempt) {
        const PlaneFitResult fit = find_dominant_plane(remaining, fit_config);
        if (fit.inlier_indices.size() < kMinGroundPoints) break;
        const Plane plane = facing_sensor(fit.plane, sensor);
        if (is_ground(plane, coarse, config)) return plane;
        std::vector<bool> inlier(remaining.size(), false);
        for (std::size_t i : fit.inlier_indices) inlier[i] = true;
        std::vector<std::size_t> rest;
        for (std::size_t i = 0; i < remaining.size(); ++i)
            if (!inlier[i]) rest.push_back(i);
        remaining = select(remaining, rest);
    }
    return std::nullopt;
}

// A view that shows too little ground to find it borrows the ground of the nearest view
// (in sequence) that fits it: the same placement of the stone.
std::optional<Plane> borrowed_ground(std::size_t view, const PointCloud& coarse,
                                     const Eigen::Vector3f& sensor,
                                     std::span<const std::optional<Plane>> grounds,
                                     const CoverageConfig& config) {
    for (std::size_t step = 1; step < grounds.size(); ++step)
        for (std::size_t other : {view - step, view + step}) {
            if (other >= grounds.size() || !grounds[other]) continue;  // wraps below 0
            const Plane plane = facing_sensor(*grounds[other], sensor);
            if (is_ground(plane, coarse, config)) return plane;
        }
    return std::nullopt;
}

// Per view, its ground facing its sensor (or none); per bin, true when it lies off its
// view's ground on the sensor's side.
std::vector<bool> above_ground(const BinnedPoints& points, const CoverageConfig& config,
                               std::vector<std::optional<Plane>>& grounds) {
    const std::size_t views = points.ranges.size();
    std::vector<PointCloud> coarse(views);
    grounds.assign(views, std::nullopt);
    tbb::parallel_for(std::size_t{0}, views, [&](std::size_t v) {
        coarse[v] = voxel_downsample(view_cloud(points, v), {.voxel_size_m = kFitVoxelM});
        grounds[v] = own_ground(coarse[v], points.sensors[v], config);
    });
    const std::vector<std::optional<Plane>> own = grounds;
    for (std::size_t v = 0; v < views; ++v)
        if (!own[v]) grounds[v] = borrowed_ground(v, coarse[v], points.sensors[v], own, config);
    std::vector<bool> keep(points.size(), true);
    for (std::size_t v = 0; v < views; ++v) {
        if (!grounds[v]) continue;
        for (std::size_t i = points.ranges[v].first; i < points.ranges[v].second; ++i)
            keep[i] = grounds[v]->signed_distance_m(points.positions[i]) > config.ground_distance_m;
    }
    return keep;
}

}  // namespace

StoneBins stone_bins(const BinnedPoints& points, const CoverageConfig& config) {
    StoneBins stone;
    const std::vector<bool> keep = above_ground(points, config, stone.grounds);
    std::vector<std::size_t> candidates;
    for (std::size_t i = 0; i < keep.size(); ++i)
        if (keep[i]) candidates.push_back(i);
    stone.indices = nearest_cluster(points, candidates, config);
    return stone;
}

std::vector<Eigen::Vector3f> hull_input(const BinnedPoints& stone,
                                        std::span<const std::optional<Plane>> grounds) {
    PointCloud input;
    input.positions = stone.positions;
    for (std::size_t v = 0; v < stone.ranges.size(); ++v) {
        if (!grounds[v]) continue;
        const Eigen::Vector3f normal = grounds[v]->normal.cast<float>();
        for (std::size_t i = stone.ranges[v].first; i < stone.ranges[v].second; ++i) {
            const Eigen::Vector3f& p = stone.positions[i];
            input.positions.push_back(p - static_cast<float>(grounds[v]->signed_distance_m(p)) *
                                              normal);
        }
    }
    // Overlapping views repeat the same surface: one point per small voxel is enough.
    return voxel_downsample(input, {.voxel_size_m = kHullVoxelM}).positions;
}

}  // namespace anascan::coverage_detail
