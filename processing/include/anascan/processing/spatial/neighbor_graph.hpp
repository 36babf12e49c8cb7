#pragma once
/// \file
/// The k nearest neighbours of every point of a cloud, computed once and shared by normal
/// estimation, normal orientation and outlier removal.
///
/// All-points k-NN on scan data is dominated by the search, so it does not go through one
/// k-d tree query per point: points are bucketed into cubic cells whose side is twice the
/// median k-th neighbour distance of a few sampled points (exact linear scans), cells are
/// numbered row by row and found through a hash table, and each cell's points are answered
/// together from the 3x3x3 block of cells around it. A query whose k-th neighbour is not
/// provably inside that block (scan borders, sparse spots) is retried on the 5x5x5 block
/// and wider, up to 9x9x9; the few still unproven (outliers) are answered by a linear
/// scan, or by a KdTree when there are more than 256, so the result is always the exact
/// k nearest neighbours.

#include <Eigen/Core>
#include <cstddef>
#include <cstdint>
#include <functional>
#include <span>
#include <vector>

namespace anascan {

struct NeighborGraphConfig {
    int k_neighbors = 15;       ///< Neighbours per point, the point itself not counted (>= 1).
    float max_radius_m = 0.0f;  ///< Neighbours farther than this are dropped; 0 = no limit.
};

/// Row i holds the neighbours of point i, closest first (equal distances by index), the
/// point itself excluded; a row holds fewer than k when the cloud is small, when
/// `max_radius_m` cuts it, or when the point is not finite (then it is empty). Non-finite
/// points are nobody's neighbour. Plain data: concurrent reads are safe.
struct NeighborGraph {
    std::size_t k = 0;                    ///< Slots per row.
    std::vector<std::uint32_t> indices;   ///< size() * k; slots past counts[i] are unused.
    std::vector<float> distances_sq_m2;   ///< Squared distances, metres squared, as indices.
    std::vector<std::uint32_t> counts;    ///< Valid neighbours per row.
    std::size_t num_exact_fallbacks = 0;  ///< Rows answered by the k-d tree (diagnostic).

    std::size_t size() const { return counts.size(); }

    /// The neighbour indices of point i, closest first.
    std::span<const std::uint32_t> neighbors(std::size_t i) const {
        return {indices.data() + i * k, counts[i]};
    }
    /// Their squared distances, metres squared.
    std::span<const float> distances_sq(std::size_t i) const {
        return {distances_sq_m2.data() + i * k, counts[i]};
    }
};

/// Exact k nearest neighbours of every point (see the file comment). Runs in parallel
/// with TBB; the result does not depend on the thread count. Fewer than 2^32 - 1 points.
NeighborGraph build_neighbor_graph(std::span<const Eigen::Vector3f> points,
                                   const NeighborGraphConfig& config);

/// One finished row: point i's neighbours, closest first, and their squared distances
/// (metres squared). The spans are valid during the call only.
using NeighborRowVisitor =
    std::function<void(std::size_t i, std::span<const std::uint32_t> neighbors,
                       std::span<const float> distances_sq_m2)>;

/// The rows of `build_neighbor_graph`, handed to `visit` as they are found instead of
/// stored: for work that needs each neighbourhood once (normal estimation), this saves
/// the graph's memory and reads each neighbourhood while it is still in cache. Rows come
/// in no particular order and from several threads at once, each row once; non-finite
/// points get no call. Returns the number of rows answered by the exact fallback.
std::size_t visit_neighbor_rows(std::span<const Eigen::Vector3f> points,
                                const NeighborGraphConfig& config, const NeighborRowVisitor& visit);

}  // namespace anascan
