#include "anascan/processing/cleaning/outlier_removal.hpp"

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <cmath>
#include <limits>

#include "anascan/processing/spatial/neighbor_graph.hpp"

namespace anascan {
namespace {

// Mean distance (metres) to the k nearest neighbours; NaN when the row is short.
std::vector<double> mean_neighbor_distances(const NeighborGraph& graph) {
    std::vector<double> mean(graph.size(), NAN);
    tbb::parallel_for(tbb::blocked_range<std::size_t>(0, graph.size(), 2048), [&](auto r) {
        for (std::size_t i = r.begin(); i < r.end(); ++i) {
            if (graph.counts[i] < graph.k) continue;
            double sum = 0.0;
            for (const float d2 : graph.distances_sq(i)) sum += std::sqrt(double(d2));
            mean[i] = sum / double(graph.k);
        }
    });
    return mean;
}

void keep_if(const PointCloud& cloud, OutlierRemovalResult& result, auto&& keep) {
    for (std::size_t i = 0; i < cloud.size(); ++i) {
        if (!cloud.positions[i].allFinite()) {
            ++result.num_non_finite;
        } else if (keep(i)) {
            result.kept_indices.push_back(i);
        }
    }
    result.num_removed = cloud.size() - result.kept_indices.size();
}

}  // namespace

OutlierRemovalResult statistical_outlier_removal(const PointCloud& cloud,
                                                 const StatisticalOutlierConfig& config) {
    OutlierRemovalResult result;
    if (cloud.empty()) {
        result.status = OutlierStatus::kEmptyCloud;
        return result;
    }
    const NeighborGraph graph =
        build_neighbor_graph(cloud.positions, {.k_neighbors = std::max(config.k_neighbors, 1)});
    const std::vector<double> mean = mean_neighbor_distances(graph);
    double sum = 0.0, sum_sq = 0.0;
    std::size_t count = 0;
    for (const double m : mean) {  // Index order: the same sums for any thread count.
        if (std::isnan(m)) continue;
        sum += m;
        sum_sq += m * m;
        ++count;
    }
    if (count < 2) {
        result.status = OutlierStatus::kTooFewPoints;
        keep_if(cloud, result, [](std::size_t) { return true; });
        return result;
    }
    result.mean_distance_m = sum / double(count);
    const double variance = (sum_sq - sum * result.mean_distance_m) / double(count - 1);
    result.sigma_distance_m = std::sqrt(std::max(variance, 0.0));
    result.threshold_m = result.mean_distance_m + config.std_ratio * result.sigma_distance_m;
    keep_if(cloud, result, [&](std::size_t i) { return mean[i] <= result.threshold_m; });
    return result;
}

OutlierRemovalResult radius_outlier_removal(const PointCloud& cloud,
                                            const RadiusOutlierConfig& config) {
    OutlierRemovalResult result;
    if (cloud.empty()) {
        result.status = OutlierStatus::kEmptyCloud;
        return result;
    }
    const std::size_t needed = std::size_t(std::max(config.min_neighbors, 0));
    if (needed == 0) {
        keep_if(cloud, result, [](std::size_t) { return true; });
        return result;
    }
    const NeighborGraph graph = build_neighbor_graph(
        cloud.positions,
        {.k_neighbors = int(needed),
         .max_radius_m = std::max(config.radius_m, std::numeric_limits<float>::min())});
    keep_if(cloud, result, [&](std::size_t i) { return graph.counts[i] >= needed; });
    return result;
}

}  // namespace anascan
