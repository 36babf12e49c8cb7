#pragma once
/// \file
/// Removal of salient outliers before registration (paper §4.1): statistical (a point
/// whose mean distance to its k nearest neighbours is unusually large) and radius based
/// (a point with too few neighbours within a radius). Both return the indices to keep;
/// `select(cloud, result.kept_indices)` applies them.

#include <cstddef>
#include <vector>

#include "anascan/processing/core/point_cloud.hpp"

namespace anascan {

struct StatisticalOutlierConfig {
    int k_neighbors = 16;    ///< Neighbours whose mean distance is the statistic (>= 1).
    double std_ratio = 2.0;  ///< Keep points with statistic <= mean + std_ratio * sigma.
};

struct RadiusOutlierConfig {
    float radius_m = 0.005f;  ///< Neighbourhood radius, metres (inclusive).
    int min_neighbors = 4;    ///< Keep points with at least this many others within radius.
};

enum class OutlierStatus {
    kOk,
    kEmptyCloud,    ///< Nothing kept, nothing removed.
    kTooFewPoints,  ///< Statistical: at most k finite points; all finite points kept.
};

struct OutlierRemovalResult {
    OutlierStatus status = OutlierStatus::kOk;
    std::vector<std::size_t> kept_indices;  ///< Increasing.
    std::size_t num_removed = 0;            ///< Including non-finite points.
    std::size_t num_non_finite = 0;         ///< Points with a NaN/inf coordinate (removed).
    double mean_distance_m = 0.0;           ///< Statistical: mean of the per-point statistic.
    double sigma_distance_m = 0.0;          ///< Statistical: its standard deviation.
    double threshold_m = 0.0;               ///< Statistical: mean + std_ratio * sigma.
};

/// Statistical outlier removal: for every point the mean distance to its k nearest
/// neighbours; points beyond mean + std_ratio * sigma of that statistic over the cloud are
/// removed. Deterministic (sums in index order), independent of the thread count.
OutlierRemovalResult statistical_outlier_removal(const PointCloud& cloud,
                                                 const StatisticalOutlierConfig& config);

/// Radius outlier removal: points with fewer than `min_neighbors` other points within
/// `radius_m` are removed.
OutlierRemovalResult radius_outlier_removal(const PointCloud& cloud,
                                            const RadiusOutlierConfig& config);

}  // namespace anascan
