#include <gtest/gtest.h>

#include <algorithm>
#include <random>
#include <vector>

#include "anascan/processing/spatial/kdtree.hpp"

namespace anascan {
namespace {

std::vector<Eigen::Vector3f> random_points(std::size_t n, std::uint32_t seed) {
    std::mt19937 rng(seed);
    std::uniform_real_distribution<float> coord(-1.0f, 1.0f);
    std::vector<Eigen::Vector3f> points(n);
    for (Eigen::Vector3f& p : points) p = {coord(rng), coord(rng), coord(rng)};
    return points;
}

// Brute-force oracle: every point with its squared distance, closest first (ties by index).
std::vector<Neighbor> brute_force(const std::vector<Eigen::Vector3f>& points,
                                  const Eigen::Vector3f& query) {
    std::vector<Neighbor> all;
    for (std::size_t i = 0; i < points.size(); ++i) {
        all.push_back({static_cast<std::uint32_t>(i), (points[i] - query).squaredNorm()});
    }
    std::sort(all.begin(), all.end(), [](const Neighbor& a, const Neighbor& b) {
        return a.distance_sq_m2 != b.distance_sq_m2 ? a.distance_sq_m2 < b.distance_sq_m2
                                                    : a.index < b.index;
    });
    return all;
}

void expect_same(const std::vector<Neighbor>& got, const std::vector<Neighbor>& expected) {
    ASSERT_EQ(got.size(), expected.size());
    for (std::size_t i = 0; i < got.size(); ++i) {
        EXPECT_EQ(got[i].index, expected[i].index) << "rank " << i;
        EXPECT_FLOAT_EQ(got[i].distance_sq_m2, expected[i].distance_sq_m2) << "rank " << i;
    }
}

class KdTreeRandom : public ::testing::Test {
protected:
    std::vector<Eigen::Vector3f> points_ = random_points(2000, 42);
    std::vector<Eigen::Vector3f> queries_ = random_points(50, 7);
    KdTree tree_{points_};
};

TEST_F(KdTreeRandom, NearestMatchesBruteForce) {
    EXPECT_EQ(tree_.size(), points_.size());
    for (const Eigen::Vector3f& q : queries_) {
        Neighbor nn;
        ASSERT_TRUE(tree_.nearest(q, nn));
        const Neighbor expected = brute_force(points_, q).front();
        EXPECT_EQ(nn.index, expected.index);
        EXPECT_FLOAT_EQ(nn.distance_sq_m2, expected.distance_sq_m2);
    }
}

TEST_F(KdTreeRandom, NearestWithinABoundIsTheNearestOrNothing) {
    // Bounds below, around and above the typical nearest distance (~0.05 for 2000 points).
    for (const float bound : {0.0f, 0.02f, 0.05f, 0.1f, 3.5f}) {
        std::size_t found = 0;
        for (const Eigen::Vector3f& q : queries_) {
            const Neighbor expected = brute_force(points_, q).front();
            Neighbor nn;
            const bool within = tree_.nearest_within(q, bound, nn);
            EXPECT_EQ(within, expected.distance_sq_m2 <= bound * bound) << "bound " << bound;
            if (!within) continue;
            ++found;
            EXPECT_EQ(nn.index, expected.index);
            EXPECT_FLOAT_EQ(nn.distance_sq_m2, expected.distance_sq_m2);
        }
        if (bound == 3.5f) {
            EXPECT_EQ(found, queries_.size());
        }
    }
    Neighbor nn;
    EXPECT_FALSE(tree_.nearest_within(queries_[0], -1.0f, nn));
    EXPECT_FALSE(KdTree(std::vector<Eigen::Vector3f>{}).nearest_within({0, 0, 0}, 1.0f, nn));
}

TEST_F(KdTreeRandom, KnnMatchesBruteForceForSeveralK) {
    std::vector<Neighbor> got;
    for (std::size_t k : {1u, 2u, 5u, 16u, 33u, 100u}) {
        for (const Eigen::Vector3f& q : queries_) {
            tree_.knn(q, k, got);
            std::vector<Neighbor> expected = brute_force(points_, q);
            expected.resize(k);
            expect_same(got, expected);
        }
    }
}

TEST_F(KdTreeRandom, RadiusMatchesBruteForce) {
    std::vector<Neighbor> got;
    for (float r : {0.0f, 0.05f, 0.2f, 0.5f}) {
        for (const Eigen::Vector3f& q : queries_) {
            tree_.radius(q, r, got);
            std::vector<Neighbor> expected = brute_force(points_, q);
            std::erase_if(expected, [r](const Neighbor& n) { return n.distance_sq_m2 > r * r; });
            expect_same(got, expected);
        }
    }
}

TEST_F(KdTreeRandom, RadiusAnyOrderHoldsTheSamePoints) {
    std::vector<Neighbor> got, sorted;
    for (const Eigen::Vector3f& q : queries_) {
        tree_.radius_any_order(q, 0.2f, got);
        tree_.radius(q, 0.2f, sorted);
        std::sort(got.begin(), got.end(), [](const Neighbor& a, const Neighbor& b) {
            return a.distance_sq_m2 != b.distance_sq_m2 ? a.distance_sq_m2 < b.distance_sq_m2
                                                        : a.index < b.index;
        });
        expect_same(got, sorted);
    }
}

TEST(KdTree, RadiusIsInclusive) {
    const std::vector<Eigen::Vector3f> points{{0, 0, 0}, {0.5f, 0, 0}, {1, 0, 0}};
    const KdTree tree(points);
    std::vector<Neighbor> got;
    tree.radius({0, 0, 0}, 0.5f, got);
    ASSERT_EQ(got.size(), 2u);
    EXPECT_EQ(got[0].index, 0u);
    EXPECT_EQ(got[1].index, 1u);
    EXPECT_FLOAT_EQ(got[1].distance_sq_m2, 0.25f);
}

TEST(KdTree, EmptyTreeReturnsNothing) {
    const std::vector<Eigen::Vector3f> none;
    const KdTree tree(none);
    EXPECT_EQ(tree.size(), 0u);
    Neighbor nn;
    EXPECT_FALSE(tree.nearest({0, 0, 0}, nn));
    std::vector<Neighbor> out{{3, 1.0f}};
    tree.knn({0, 0, 0}, 4, out);
    EXPECT_TRUE(out.empty());
    out = {{3, 1.0f}};
    tree.radius({0, 0, 0}, 10.0f, out);
    EXPECT_TRUE(out.empty());
}

TEST(KdTree, DuplicatePointsAreAllFound) {
    std::vector<Eigen::Vector3f> points(40, Eigen::Vector3f(0.1f, 0.2f, 0.3f));
    points.emplace_back(1.0f, 1.0f, 1.0f);
    const KdTree tree(points, KdTree::Config{.max_leaf_size = 4});
    std::vector<Neighbor> out;
    tree.radius({0.1f, 0.2f, 0.3f}, 0.01f, out);
    ASSERT_EQ(out.size(), 40u);
    for (std::size_t i = 0; i < out.size(); ++i) {
        EXPECT_EQ(out[i].index, i);  // Equal distances come in index order.
        EXPECT_EQ(out[i].distance_sq_m2, 0.0f);
    }
    tree.knn({0.1f, 0.2f, 0.3f}, 10, out);
    ASSERT_EQ(out.size(), 10u);
    for (const Neighbor& n : out) EXPECT_LT(n.index, 40u);
    Neighbor nn;
    ASSERT_TRUE(tree.nearest({0.9f, 0.9f, 0.9f}, nn));
    EXPECT_EQ(nn.index, 40u);
}

TEST(KdTree, KLargerThanSizeReturnsAllPointsSorted) {
    const std::vector<Eigen::Vector3f> points = random_points(7, 3);
    const KdTree tree(points);
    std::vector<Neighbor> out;
    tree.knn({0, 0, 0}, 50, out);
    expect_same(out, brute_force(points, {0, 0, 0}));
    tree.knn({0, 0, 0}, 0, out);
    EXPECT_TRUE(out.empty());
}

TEST(KdTree, MovedTreeKeepsAnswering) {
    const std::vector<Eigen::Vector3f> points = random_points(100, 5);
    KdTree first(points);
    KdTree second = std::move(first);
    Neighbor nn;
    ASSERT_TRUE(second.nearest(points[17], nn));
    EXPECT_EQ(nn.index, 17u);
    EXPECT_EQ(nn.distance_sq_m2, 0.0f);
}

}  // namespace
}  // namespace anascan
