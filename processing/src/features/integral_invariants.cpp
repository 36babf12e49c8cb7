#include "anascan/processing/features/integral_invariants.hpp"

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <chrono>
#include <cmath>

#include "anascan/processing/spatial/kdtree.hpp"
#include "anascan/processing/spatial/min_distance_sampling.hpp"
#include "anascan/processing/spatial/voxel_grid.hpp"

namespace anascan {
namespace {

bool usable_normal(const Eigen::Vector3f& n) { return n.allFinite() && n.squaredNorm() > 0.25f; }

bool config_valid(const IntegralInvariantConfig& config) {
    for (std::size_t k = 0; k < kInvariantRadii; ++k) {
        if (!(config.radii_m[k] > 0.0) || !std::isfinite(config.radii_m[k])) return false;
    }
    return config.site_spacing_m >= 0.0 && config.sample_spacing_fraction > 0.0 &&
           config.max_centroid_offset_fraction > 0.0 && config.chunk_size > 0;
}

bool input_valid(const PointCloud& cloud) {
    return !cloud.empty() && cloud.has_normals() && cloud.attributes_consistent();
}

/// Sites: the point nearest each voxel mean (a true surface sample: a voxel mean lies
/// inside a convex surface, which would bias h̄), with its normal.
void place_sites(const PointCloud& cloud, double spacing_m, bool frame_free,
                 IntegralInvariantResult& result) {
    PointCloud oriented;
    for (std::size_t i = 0; i < cloud.size(); ++i) {
        if (!usable_normal(cloud.normals[i]) || !cloud.positions[i].allFinite()) continue;
        oriented.positions.push_back(cloud.positions[i]);
        oriented.normals.push_back(cloud.normals[i]);
    }
    if (frame_free) {
        for (std::uint32_t i : min_distance_sample(oriented, spacing_m)) {
            result.site_positions.push_back(oriented.positions[i]);
            result.site_normals.push_back(oriented.normals[i].normalized());
        }
        return;
    }
    const PointCloud means = voxel_downsample(oriented, {.voxel_size_m = spacing_m});
    const KdTree tree(oriented.positions);
    std::vector<std::uint32_t> chosen;
    chosen.reserve(means.size());
    Neighbor nearest;
    for (const Eigen::Vector3f& mean : means.positions) {
        if (tree.nearest(mean, nearest)) chosen.push_back(nearest.index);
    }
    std::sort(chosen.begin(), chosen.end());
    chosen.erase(std::unique(chosen.begin(), chosen.end()), chosen.end());
    for (std::uint32_t i : chosen) {
        result.site_positions.push_back(oriented.positions[i]);
        result.site_normals.push_back(oriented.normals[i].normalized());
    }
}

PointCloud downsample(const PointCloud& cloud, double spacing_m, bool frame_free) {
    if (!frame_free) return voxel_downsample(cloud, {.voxel_size_m = spacing_m});
    PointCloud out;
    for (std::uint32_t i : min_distance_sample(cloud, spacing_m)) {
        out.positions.push_back(cloud.positions[i]);
        out.normals.push_back(cloud.normals[i]);
    }
    return out;
}

enum class SiteOutcome : std::uint8_t { kValid, kBoundary, kSparse };

/// One site at one radius: mean height of the samples within r over the tangent plane
/// given by their mean normal, V_r ≈ 1/2 + 3 h̄ / (4 r).
SiteOutcome site_volume(const PointCloud& samples, const KdTree& tree, const Eigen::Vector3f& p,
                        float radius_m, const IntegralInvariantConfig& config,
                        std::vector<Neighbor>& neighbors, float& volume) {
    tree.radius_any_order(p, radius_m, neighbors);
    if (neighbors.size() < config.min_neighbors) return SiteOutcome::kSparse;
    Eigen::Vector3d offset_sum = Eigen::Vector3d::Zero();
    Eigen::Vector3d normal_sum = Eigen::Vector3d::Zero();
    for (const Neighbor& nb : neighbors) {
        offset_sum += (samples.positions[nb.index] - p).cast<double>();
        const Eigen::Vector3f& n = samples.normals[nb.index];
        if (usable_normal(n)) normal_sum += n.cast<double>();
    }
    if (normal_sum.norm() < 0.5 * static_cast<double>(neighbors.size())) {
        return SiteOutcome::kSparse;  // Too few usable normals or a fold inside the ball.
    }
    const Eigen::Vector3d n = normal_sum.normalized();
    const Eigen::Vector3d centroid_offset = offset_sum / static_cast<double>(neighbors.size());
    const double height_m = n.dot(centroid_offset);
    const double tangential_m = (centroid_offset - height_m * n).norm();
    if (tangential_m > config.max_centroid_offset_fraction * radius_m) {
        return SiteOutcome::kBoundary;
    }
    volume = static_cast<float>(0.5 + 0.75 * height_m / radius_m);
    return SiteOutcome::kValid;
}

/// All sites at radius index k; one slot per site, so the result is thread-count free.
void compute_radius(const PointCloud& cloud, std::size_t k, const IntegralInvariantConfig& config,
                    IntegralInvariantResult& result) {
    const double radius_m = config.radii_m[k];
    const PointCloud samples =
        downsample(cloud, radius_m * config.sample_spacing_fraction, config.frame_free_sampling);
    const KdTree tree(samples.positions);
    const std::size_t n = result.site_positions.size();
    std::vector<SiteOutcome> outcome(n, SiteOutcome::kSparse);
    tbb::parallel_for(tbb::blocked_range<std::size_t>(0, n, config.chunk_size), [&](auto range) {
        std::vector<Neighbor> neighbors;
        for (std::size_t i = range.begin(); i < range.end(); ++i) {
            outcome[i] =
                site_volume(samples, tree, result.site_positions[i], static_cast<float>(radius_m),
                            config, neighbors, result.volume[i][k]);
        }
    });
    for (std::size_t i = 0; i < n; ++i) {
        if (outcome[i] == SiteOutcome::kValid) {
            result.valid_bits[i] |= static_cast<std::uint8_t>(1u << k);
            ++result.valid_count[k];
        } else if (outcome[i] == SiteOutcome::kBoundary) {
            ++result.boundary_count[k];
        } else {
            ++result.sparse_count[k];
        }
    }
}

}  // namespace

double median_sample_spacing_m(const PointCloud& cloud, std::size_t max_samples) {
    if (cloud.size() < 2 || max_samples == 0) return 0.0;
    const KdTree tree(cloud.positions);
    const std::size_t stride = std::max<std::size_t>(1, cloud.size() / max_samples);
    std::vector<float> distances;
    std::vector<Neighbor> neighbors;
    for (std::size_t i = 0; i < cloud.size(); i += stride) {
        if (!cloud.positions[i].allFinite()) continue;
        tree.knn(cloud.positions[i], 2, neighbors);
        if (neighbors.size() == 2) distances.push_back(std::sqrt(neighbors[1].distance_sq_m2));
    }
    if (distances.empty()) return 0.0;
    auto middle = distances.begin() + distances.size() / 2;
    std::nth_element(distances.begin(), middle, distances.end());
    return *middle;
}

InvariantRadii geometric_radii_m(double smallest_m) {
    return {smallest_m, 1.5 * smallest_m, 2.25 * smallest_m, 3.375 * smallest_m};
}

InvariantRadii radii_for_object_size_m(double object_size_m) {
    return geometric_radii_m(0.04 * object_size_m);
}

InvariantRadii radii_for_sample_spacing_m(double spacing_m) {
    return geometric_radii_m(12.0 * spacing_m);
}

IntegralInvariantResult compute_integral_invariants(const PointCloud& cloud,
                                                    const IntegralInvariantConfig& config) {
    const auto start = std::chrono::steady_clock::now();
    IntegralInvariantResult result;
    result.radii_m = config.radii_m;
    result.origin_m = cloud.origin_m;
    if (!config_valid(config) || !input_valid(cloud)) return result;
    result.site_spacing_m =
        config.site_spacing_m > 0.0 ? config.site_spacing_m : 0.25 * config.radii_m[0];
    place_sites(cloud, result.site_spacing_m, config.frame_free_sampling, result);
    result.volume.assign(result.site_positions.size(), {});
    result.valid_bits.assign(result.site_positions.size(), 0);
    for (std::size_t k = 0; k < kInvariantRadii; ++k) compute_radius(cloud, k, config, result);
    result.status = IntegralInvariantStatus::kOk;
    result.time_s = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    return result;
}

}  // namespace anascan
