#pragma once
/// \file
/// Nearest-neighbour search over a cloud's positions (a thin wrapper over nanoflann; the
/// nanoflann API of Debian 1.4.3 stays inside kdtree.cpp).

#include <Eigen/Core>
#include <cstddef>
#include <cstdint>
#include <memory>
#include <span>
#include <vector>

namespace anascan {

/// One neighbour: index into the indexed points and squared distance (metres squared).
struct Neighbor {
    std::uint32_t index = 0;
    float distance_sq_m2 = 0.0f;
};

/// Static k-d tree over points the caller owns (no copy: the span must outlive the tree).
///
/// Thread safety: construction is single-threaded; all const queries may run concurrently
/// from many threads once constructed.
class KdTree {
public:
    struct Config {
        int max_leaf_size = 16;  ///< Points per leaf; 10-20 is fastest for 3-D queries.
    };

    explicit KdTree(std::span<const Eigen::Vector3f> points);
    KdTree(std::span<const Eigen::Vector3f> points, Config config);
    ~KdTree();
    KdTree(KdTree&&) noexcept;
    KdTree& operator=(KdTree&&) noexcept;
    KdTree(const KdTree&) = delete;
    KdTree& operator=(const KdTree&) = delete;

    std::size_t size() const;
    /// Bytes of the index (nodes and the permutation; the points belong to the caller).
    std::size_t memory_bytes() const;

    /// The nearest point; `false` when the tree is empty.
    bool nearest(const Eigen::Vector3f& query, Neighbor& out) const;

    /// The nearest point at most `max_distance_m` away (inclusive); `false` when there is
    /// none. The same point as `nearest` when it lies within the bound, found without
    /// visiting the branches beyond it: ICP correspondences past their gate cost little.
    bool nearest_within(const Eigen::Vector3f& query, float max_distance_m, Neighbor& out) const;

    /// Up to k nearest points, closest first (fewer when the tree holds fewer than k).
    void knn(const Eigen::Vector3f& query, std::size_t k, std::vector<Neighbor>& out) const;

    /// All points within `radius_m` (inclusive), closest first.
    void radius(const Eigen::Vector3f& query, float radius_m, std::vector<Neighbor>& out) const;

    /// The same points as `radius`, in the tree's traversal order (deterministic, not
    /// sorted): for sums and counts, where sorting would cost more than the search.
    void radius_any_order(const Eigen::Vector3f& query, float radius_m,
                          std::vector<Neighbor>& out) const;

private:
    struct Impl;
    std::unique_ptr<Impl> impl_;
};

}  // namespace anascan
