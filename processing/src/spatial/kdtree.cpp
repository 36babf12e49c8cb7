#include "anascan/processing/spatial/kdtree.hpp"

#include <algorithm>
#include <cassert>
#include <cmath>
#include <limits>
#include <nanoflann.hpp>
#include <utility>

namespace anascan {
namespace {

// nanoflann's view of the caller's points: no copy, only the span.
struct PointsAdaptor {
    std::span<const Eigen::Vector3f> points;

    std::size_t kdtree_get_point_count() const { return points.size(); }
    float kdtree_get_pt(std::uint32_t index, std::size_t dim) const {
        return points[index][static_cast<Eigen::Index>(dim)];
    }
    template <class BoundingBox>
    bool kdtree_get_bbox(BoundingBox& /*bbox*/) const {
        return false;  // Let nanoflann compute the bounds.
    }
};

using NanoflannTree =
    nanoflann::KDTreeSingleIndexAdaptor<nanoflann::L2_Simple_Adaptor<float, PointsAdaptor>,
                                        PointsAdaptor, 3, std::uint32_t>;

// nanoflann's result set for one neighbour that starts with a bound instead of infinity, so
// the search prunes every branch beyond it. Visits the same nodes in the same order as
// KNNResultSet(1) until then, so ties resolve alike.
class BoundedNearest {
public:
    explicit BoundedNearest(float bound_sq) : worst_(bound_sq) {}
    std::size_t size() const { return found_ ? 1 : 0; }
    bool full() const { return true; }
    bool addPoint(float distance_sq, std::uint32_t index) {
        if (distance_sq < worst_) {
            worst_ = distance_sq;
            index_ = index;
            found_ = true;
        }
        return true;
    }
    float worstDist() const { return worst_; }
    std::uint32_t index() const { return index_; }

private:
    float worst_;
    std::uint32_t index_ = 0;
    bool found_ = false;
};

// Closest first; equal distances by index, so results are deterministic.
void sort_closest_first(std::vector<Neighbor>& out) {
    std::sort(out.begin(), out.end(), [](const Neighbor& a, const Neighbor& b) {
        return a.distance_sq_m2 != b.distance_sq_m2 ? a.distance_sq_m2 < b.distance_sq_m2
                                                    : a.index < b.index;
    });
}

}  // namespace

struct KdTree::Impl {
    // The adaptor must not move while the tree refers to it; Impl lives behind a unique_ptr.
    PointsAdaptor adaptor;
    NanoflannTree tree;

    Impl(std::span<const Eigen::Vector3f> points, const Config& config)
        : adaptor{points},
          tree(3, adaptor,
               nanoflann::KDTreeSingleIndexAdaptorParams(
                   static_cast<std::size_t>(std::max(config.max_leaf_size, 1)))) {}
};

KdTree::KdTree(std::span<const Eigen::Vector3f> points) : KdTree(points, Config{}) {}

KdTree::KdTree(std::span<const Eigen::Vector3f> points, Config config) {
    assert(points.size() < std::numeric_limits<std::uint32_t>::max());
    impl_ = std::make_unique<Impl>(points, config);
}

KdTree::~KdTree() = default;
KdTree::KdTree(KdTree&&) noexcept = default;
KdTree& KdTree::operator=(KdTree&&) noexcept = default;

std::size_t KdTree::size() const { return impl_ ? impl_->adaptor.points.size() : 0; }

std::size_t KdTree::memory_bytes() const {
    return impl_ ? impl_->tree.usedMemory(impl_->tree) + sizeof(Impl) : 0;
}

bool KdTree::nearest(const Eigen::Vector3f& query, Neighbor& out) const {
    if (size() == 0) return false;
    std::uint32_t index = 0;
    float distance_sq = 0.0f;
    nanoflann::KNNResultSet<float, std::uint32_t> result(1);
    result.init(&index, &distance_sq);
    impl_->tree.findNeighbors(result, query.data(), nanoflann::SearchParams());
    if (result.size() == 0) return false;
    out = Neighbor{index, distance_sq};
    return true;
}

bool KdTree::nearest_within(const Eigen::Vector3f& query, float max_distance_m,
                            Neighbor& out) const {
    if (size() == 0 || !(max_distance_m >= 0.0f)) return false;
    // Points strictly below the bound are taken; the next float makes it inclusive.
    BoundedNearest result(
        std::nextafter(max_distance_m * max_distance_m, std::numeric_limits<float>::infinity()));
    impl_->tree.findNeighbors(result, query.data(), nanoflann::SearchParams());
    if (result.size() == 0) return false;
    out = Neighbor{result.index(), result.worstDist()};
    return true;
}

void KdTree::knn(const Eigen::Vector3f& query, std::size_t k, std::vector<Neighbor>& out) const {
    out.clear();
    const std::size_t wanted = std::min(k, size());
    if (wanted == 0) return;
    std::vector<std::uint32_t> indices(wanted);
    std::vector<float> distances_sq(wanted);
    nanoflann::KNNResultSet<float, std::uint32_t> result(wanted);
    result.init(indices.data(), distances_sq.data());
    impl_->tree.findNeighbors(result, query.data(), nanoflann::SearchParams());
    out.reserve(result.size());
    for (std::size_t i = 0; i < result.size(); ++i) {
        out.push_back(Neighbor{indices[i], distances_sq[i]});
    }
    sort_closest_first(out);
}

void KdTree::radius_any_order(const Eigen::Vector3f& query, float radius_m,
                              std::vector<Neighbor>& out) const {
    out.clear();
    if (size() == 0 || !(radius_m >= 0.0f)) return;
    const float radius_sq = radius_m * radius_m;
    // nanoflann keeps distances strictly below its bound; the next float makes it inclusive.
    const float bound = std::nextafter(radius_sq, std::numeric_limits<float>::infinity());
    std::vector<std::pair<std::uint32_t, float>> found;
    impl_->tree.radiusSearch(query.data(), bound, found, nanoflann::SearchParams(32, 0.0f, false));
    out.reserve(found.size());
    for (const auto& [index, distance_sq] : found) {
        if (distance_sq <= radius_sq) out.push_back(Neighbor{index, distance_sq});
    }
}

void KdTree::radius(const Eigen::Vector3f& query, float radius_m,
                    std::vector<Neighbor>& out) const {
    radius_any_order(query, radius_m, out);
    sort_closest_first(out);
}

}  // namespace anascan
