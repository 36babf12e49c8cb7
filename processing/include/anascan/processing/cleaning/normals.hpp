#pragma once
/// \file
/// Surface normals of a point cloud by local PCA over the k nearest neighbours, and their
/// orientation: toward a known sensor position, or consistently by propagation over the
/// neighbour graph (Hoppe et al. 1992) when no sensor is known. Paper §4.1 computes
/// oriented normals after outlier removal [Mitra and Nguyen 2003]; k-NN PCA is their
/// estimator with a fixed neighbourhood size.
///
/// Library code: no I/O, parallel loops with TBB, results independent of the thread count.

#include <Eigen/Core>
#include <cstddef>
#include <vector>

#include "anascan/processing/core/point_cloud.hpp"
#include "anascan/processing/spatial/neighbor_graph.hpp"

namespace anascan {

struct NormalEstimationConfig {
    int k_neighbors = 15;       ///< Neighbours besides the point itself (PCA uses k + 1 points).
    float max_radius_m = 0.0f;  ///< Neighbours farther than this are ignored; 0 = no limit.
    int min_neighbors = 3;      ///< Fewer usable neighbours: zero normal, counted (>= 2).
    /// Keep the neighbour graph in the result (for `orient_consistently`). Without it each
    /// neighbourhood is fitted as soon as it is found and none is stored, which saves
    /// k * 8 bytes per point and about a third of the time (docs/preprocessing.md).
    bool keep_graph = false;
};

enum class NormalStatus {
    kOk,          ///< Every finite point with enough neighbours got a normal.
    kEmptyCloud,  ///< Nothing to do.
};

struct NormalEstimationResult {
    NormalStatus status = NormalStatus::kOk;
    std::size_t num_estimated = 0;          ///< Points that received a unit normal.
    std::size_t num_too_few_neighbors = 0;  ///< Zero normal: isolated or non-finite point.
    std::size_t num_degenerate = 0;         ///< Zero normal: neighbourhood all one point.
    /// Surface variation λ0 / (λ0 + λ1 + λ2) of the local covariance, 0 (flat) to 1/3
    /// (isotropic), per point; 0 where the normal is zero.
    std::vector<float> curvature;
    /// The neighbour graph used, when `keep_graph` was set (else empty); pass it on to
    /// `orient_consistently` to avoid a rebuild.
    NeighborGraph graph;
};

/// Fills `cloud.normals` with unit normals by PCA over each point's k nearest neighbours:
/// the eigenvector of the smallest eigenvalue of the neighbourhood covariance, accumulated
/// in double relative to the neighbourhood centroid. When the cloud already had normals,
/// each new normal keeps the side of the old one; otherwise the sign is arbitrary (call an
/// `orient_*` function). Points without `min_neighbors` neighbours get a zero normal.
NormalEstimationResult estimate_normals(PointCloud& cloud, const NormalEstimationConfig& config);

struct OrientationResult {
    std::size_t num_flipped = 0;     ///< Normals whose sign changed.
    std::size_t num_unoriented = 0;  ///< Zero normals (left as they are).
    std::size_t num_components = 0;  ///< Connected parts oriented separately (graph only).
};

/// Flips every normal to face `sensor_origin_m` (a position in the cloud's local frame,
/// metres): n · (sensor - p) >= 0 afterwards. Zero normals stay zero.
OrientationResult orient_toward(PointCloud& cloud, const Eigen::Vector3f& sensor_origin_m);

struct ConsistentOrientationConfig {
    int k_neighbors = 15;  ///< Graph size when no graph is passed in.
};

/// Orients normals consistently without a sensor (Hoppe et al. 1992): over the symmetric
/// k-NN graph with edge weight 1 - |n_i · n_j|, a minimum spanning forest is built and
/// signs are propagated from each tree's root, so orientation crosses the smoothest edges
/// first. Each connected part is then flipped as a whole so that its normals point, on
/// average, away from its centroid (outward on a closed surface); a flat part, where that
/// is undecided, is turned toward +z of the local frame. `graph` is the cloud's neighbour
/// graph, e.g. the one `estimate_normals` kept; when it does not match the cloud (an empty
/// graph), one is built with the default k.
OrientationResult orient_consistently(PointCloud& cloud, const NeighborGraph& graph);

/// Same, building the neighbour graph first.
OrientationResult orient_consistently(PointCloud& cloud, const ConsistentOrientationConfig& config);

}  // namespace anascan
