#include "anascan/processing/features/feature_patches.hpp"

#include <Eigen/Eigenvalues>
#include <algorithm>
#include <cmath>
#include <cstdint>

#include "anascan/processing/spatial/kdtree.hpp"

namespace anascan {
namespace {

using Adjacency = std::vector<std::vector<std::uint32_t>>;

bool config_valid(const FeaturePatchConfig& config) {
    for (double q : config.level_quantiles) {
        if (!(q >= 0.0 && q < 1.0)) return false;
    }
    return config.min_deviation >= 0.0 && config.neighbor_spacing_factor > 0.0 &&
           config.min_sites > 0;
}

double quantile(std::vector<double>& values, double q) {
    if (values.empty()) return 0.0;
    const auto at = static_cast<std::size_t>(q * static_cast<double>(values.size() - 1));
    std::nth_element(values.begin(), values.begin() + at, values.end());
    return values[at];
}

/// Deviation of V from 1/2 on `side`, or a negative value when on the other side.
double side_deviation(float volume, CurvatureSide side) {
    const double d = static_cast<double>(volume) - 0.5;
    return side == CurvatureSide::kConcave ? d : -d;
}

Adjacency site_adjacency(const IntegralInvariantResult& invariants, double radius_m) {
    const KdTree tree(invariants.site_positions);
    Adjacency adjacency(invariants.site_positions.size());
    std::vector<Neighbor> neighbors;
    for (std::size_t i = 0; i < adjacency.size(); ++i) {
        tree.radius(invariants.site_positions[i], static_cast<float>(radius_m), neighbors);
        for (const Neighbor& nb : neighbors) {
            if (nb.index != i) adjacency[i].push_back(nb.index);
        }
    }
    return adjacency;
}

/// Barycentre, mean normal, principal extent of the sites of one region.
FeaturePatch describe_region(const IntegralInvariantResult& invariants,
                             const std::vector<std::uint32_t>& sites, std::size_t radius_index) {
    FeaturePatch patch;
    patch.radius_index = radius_index;
    patch.site_count = sites.size();
    Eigen::Vector3d sum = Eigen::Vector3d::Zero(), normal_sum = Eigen::Vector3d::Zero();
    double volume_sum = 0.0;
    for (std::uint32_t s : sites) {
        sum += invariants.site_positions[s].cast<double>();
        normal_sum += invariants.site_normals[s].cast<double>();
        volume_sum += invariants.volume[s][radius_index];
    }
    const double n = static_cast<double>(sites.size());
    const Eigen::Vector3d mean = sum / n;
    Eigen::Matrix3d covariance = Eigen::Matrix3d::Zero();
    for (std::uint32_t s : sites) {
        const Eigen::Vector3d d = invariants.site_positions[s].cast<double>() - mean;
        covariance += d * d.transpose();
    }
    const Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> eigen(covariance / n);
    const Eigen::Vector3d values = eigen.eigenvalues().cwiseMax(0.0).cwiseSqrt();
    patch.extent_m = Eigen::Vector3d(values[2], values[1], values[0]);
    patch.barycentre_m = invariants.origin_m + mean;
    patch.normal = normal_sum.norm() > 0.0 ? normal_sum.normalized() : Eigen::Vector3d::UnitZ();
    patch.mean_volume = volume_sum / n;
    return patch;
}

/// Connected components of the sites with `member` set, grown in site order.
std::vector<std::vector<std::uint32_t>> components(const Adjacency& adjacency,
                                                   const std::vector<std::uint8_t>& member) {
    std::vector<std::vector<std::uint32_t>> regions;
    std::vector<std::uint8_t> seen(member.size(), 0);
    for (std::uint32_t seed = 0; seed < member.size(); ++seed) {
        if (!member[seed] || seen[seed]) continue;
        std::vector<std::uint32_t> region{seed};
        seen[seed] = 1;
        for (std::size_t head = 0; head < region.size(); ++head) {
            for (std::uint32_t next : adjacency[region[head]]) {
                if (!member[next] || seen[next]) continue;
                seen[next] = 1;
                region.push_back(next);
            }
        }
        regions.push_back(std::move(region));
    }
    return regions;
}

void add_level_patches(const IntegralInvariantResult& invariants, const Adjacency& adjacency,
                       std::size_t k, CurvatureSide side, std::size_t level, double threshold,
                       const FeaturePatchConfig& config, FeaturePatchResult& result) {
    std::vector<std::uint8_t> member(invariants.site_positions.size(), 0);
    for (std::size_t i = 0; i < member.size(); ++i) {
        member[i] =
            invariants.is_valid(i, k) && side_deviation(invariants.volume[i][k], side) >= threshold;
    }
    for (const auto& region : components(adjacency, member)) {
        if (region.size() < config.min_sites) continue;
        FeaturePatch patch = describe_region(invariants, region, k);
        patch.side = side;
        patch.level = level;
        result.patches.push_back(patch);
        ++result.patch_count[k];
    }
}

}  // namespace

SaliencyLevels saliency_levels(std::span<const IntegralInvariantResult* const> scans,
                               const FeaturePatchConfig& config) {
    SaliencyLevels levels;
    for (std::size_t k = 0; k < kInvariantRadii; ++k) {
        for (CurvatureSide side : {CurvatureSide::kConvex, CurvatureSide::kConcave}) {
            std::vector<double> deviations;
            for (const IntegralInvariantResult* scan : scans) {
                for (std::size_t i = 0; i < scan->volume.size(); ++i) {
                    const double d = side_deviation(scan->volume[i][k], side);
                    if (scan->is_valid(i, k) && d > 0.0) deviations.push_back(d);
                }
            }
            auto& out = levels.deviation[k][static_cast<std::size_t>(side)];
            for (std::size_t l = 0; l < kSaliencyLevels; ++l) {
                out[l] =
                    std::max(config.min_deviation, quantile(deviations, config.level_quantiles[l]));
            }
        }
    }
    return levels;
}

FeaturePatchResult extract_feature_patches(const IntegralInvariantResult& invariants,
                                           const SaliencyLevels& levels,
                                           const FeaturePatchConfig& config) {
    FeaturePatchResult result;
    if (invariants.status != IntegralInvariantStatus::kOk || !config_valid(config)) return result;
    const Adjacency adjacency =
        site_adjacency(invariants, config.neighbor_spacing_factor * invariants.site_spacing_m);
    for (std::size_t k = 0; k < kInvariantRadii; ++k) {
        for (CurvatureSide side : {CurvatureSide::kConvex, CurvatureSide::kConcave}) {
            for (std::size_t l = 0; l < kSaliencyLevels; ++l) {
                const double threshold = levels.deviation[k][static_cast<std::size_t>(side)][l];
                add_level_patches(invariants, adjacency, k, side, l, threshold, config, result);
            }
        }
    }
    result.status = FeaturePatchStatus::kOk;
    return result;
}

FeaturePatchResult extract_feature_patches(const IntegralInvariantResult& invariants,
                                           const FeaturePatchConfig& config) {
    const IntegralInvariantResult* scans[] = {&invariants};
    return extract_feature_patches(invariants, saliency_levels(scans, config), config);
}

}  // namespace anascan
