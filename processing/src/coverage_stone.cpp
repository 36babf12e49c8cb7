// Coverage, the stone's points without ground truth. Per view, the ground is the largest
// plane with (almost) nothing beyond it as seen from the sensor: a face of the stone has
// the ground or other faces behind it, the ground under a stone has nothing. The points on
// the sensor's side of the ground (farther than ground_distance_m) are kept. Of those, the
// connected cluster of occupied voxels nearest the median point is the stone; the rest
// (tent, tools, neighbouring stones) is background.

#include <tbb/parallel_for.h>

#include <algorithm>
#include <optional>
#include <unordered_map>

#include "anascan/processing/plane_removal.hpp"
#include "anascan/processing/voxel_grid.hpp"
#include "coverage_steps.hpp"

namespace anascan::coverage_detail {
namespace {

constexpr double kFitVoxelM = 0.008;         // plane fits on a coarse copy of the view
constexpr double kMaxBehindFraction = 0.02;  // of the view's points, beyond the ground
constexpr int kMaxPlanes = 4;                // candidate planes tried per view

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

std::optional<Plane> ground_plane(const PointCloud& coarse, const Eigen::Vector3f& sensor,
                                  const CoverageConfig& config) {
    PointCloud remaining = coarse;
    const PlaneFitConfig fit_config{.distance_threshold_m = config.ground_distance_m};
    for (int attempt = 0; attempt < kMaxPlanes && remaining.size() >= 3; ++attempt) {
        const PlaneFitResult fit = find_dominant_plane(remaining, fit_config);
        if (fit.inlier_indices.size() < std::max<std::size_t>(30, coarse.size() / 20)) break;
        const Plane plane = facing_sensor(fit.plane, sensor);
        const auto behind = std::count_if(
            coarse.positions.begin(), coarse.positions.end(), [&](const Eigen::Vector3f& p) {
                return plane.signed_distance_m(p) < -2.0 * config.ground_distance_m;
            });
        if (static_cast<double>(behind) <= kMaxBehindFraction * static_cast<double>(coarse.size()))
            return plane;
        std::vector<bool> inlier(remaining.size(), false);
        for (std::size_t i : fit.inlier_indices) inlier[i] = true;
        std::vector<std::size_t> rest;
        for (std::size_t i = 0; i < remaining.size(); ++i)
            if (!inlier[i]) rest.push_back(i);
        remaining = select(remaining, rest);
    }
    return std::nullopt;
}

// Per bin: true when it lies off its view's ground, on the sensor's side.
std::vector<bool> above_ground(const BinnedPoints& points, const CoverageConfig& config) {
    std::vector<bool> keep(points.size(), true);
    tbb::parallel_for(std::size_t{0}, points.ranges.size(), [&](std::size_t v) {
        const PointCloud coarse =
            voxel_downsample(view_cloud(points, v), {.voxel_size_m = kFitVoxelM});
        const std::optional<Plane> ground = ground_plane(coarse, points.sensors[v], config);
        if (!ground) return;
        for (std::size_t i = points.ranges[v].first; i < points.ranges[v].second; ++i)
            keep[i] = ground->signed_distance_m(points.positions[i]) > config.ground_distance_m;
    });
    return keep;
}

}  // namespace

std::vector<std::size_t> stone_bins(const BinnedPoints& points, const CoverageConfig& config) {
    const std::vector<bool> keep = above_ground(points, config);
    std::vector<std::size_t> candidates;
    for (std::size_t i = 0; i < keep.size(); ++i)
        if (keep[i]) candidates.push_back(i);
    return nearest_cluster(points, candidates, config);
}

}  // namespace anascan::coverage_detail
