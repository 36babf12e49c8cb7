// build_neighbor_graph is exact: the same rows (indices, closest first, ties by index) as a
// brute-force search, for dense surface points, isolated outliers (answered by the
// linear-scan fallback) and many outliers, duplicates, a radius limit and NaNs.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <random>
#include <utility>
#include <vector>

#include "anascan/processing/spatial/neighbor_graph.hpp"

namespace anascan {
namespace {

// Brute-force rows with the graph's conventions (float distances as the graph computes).
std::vector<std::vector<std::uint32_t>> brute_force(const std::vector<Eigen::Vector3f>& p,
                                                    std::size_t k, float max_radius_m) {
    const float max_d2 =
        max_radius_m > 0.0f ? max_radius_m * max_radius_m : std::numeric_limits<float>::infinity();
    std::vector<std::vector<std::uint32_t>> rows(p.size());
    for (std::size_t i = 0; i < p.size(); ++i) {
        if (!p[i].allFinite()) continue;
        std::vector<std::pair<float, std::uint32_t>> all;
        for (std::size_t j = 0; j < p.size(); ++j) {
            if (j == i || !p[j].allFinite()) continue;
            const float dx = p[j].x() - p[i].x(), dy = p[j].y() - p[i].y(),
                        dz = p[j].z() - p[i].z();
            const float d2 = dx * dx + dy * dy + dz * dz;
            if (d2 <= max_d2) all.emplace_back(d2, std::uint32_t(j));
        }
        std::sort(all.begin(), all.end());
        for (std::size_t r = 0; r < std::min(k, all.size()); ++r) rows[i].push_back(all[r].second);
    }
    return rows;
}

// A wavy sheet (1 mm spacing), `outliers` points scattered far off it, a few exact
// duplicates and a NaN.
std::vector<Eigen::Vector3f> test_points(std::size_t outliers, unsigned seed) {
    std::mt19937 rng(seed);
    std::uniform_real_distribution<float> jitter(-0.0002f, 0.0002f), far(-0.5f, 0.5f);
    std::vector<Eigen::Vector3f> p;
    for (int i = 0; i < 40; ++i) {
        for (int j = 0; j < 40; ++j) {
            const float x = 0.001f * float(i) + jitter(rng), y = 0.001f * float(j) + jitter(rng);
            p.emplace_back(x, y, 0.003f * std::sin(x * 200.0f) + jitter(rng));
        }
    }
    for (std::size_t o = 0; o < outliers; ++o) p.emplace_back(far(rng), far(rng), far(rng));
    for (int d = 0; d < 5; ++d) p.push_back(p[std::size_t(100 * d + 7)]);
    p.emplace_back(std::nanf(""), 0.0f, 0.0f);
    return p;
}

void expect_exact(const std::vector<Eigen::Vector3f>& p, int k, float max_radius_m) {
    const NeighborGraph graph =
        build_neighbor_graph(p, {.k_neighbors = k, .max_radius_m = max_radius_m});
    const auto expected = brute_force(p, std::size_t(k), max_radius_m);
    ASSERT_EQ(graph.size(), p.size());
    std::size_t mismatches = 0;
    for (std::size_t i = 0; i < p.size(); ++i) {
        const auto row = graph.neighbors(i);
        const bool same =
            std::equal(row.begin(), row.end(), expected[i].begin(), expected[i].end());
        if (!same && ++mismatches <= 3) ADD_FAILURE() << "row " << i << " differs";
    }
    EXPECT_EQ(mismatches, 0u);
}

TEST(NeighborGraph, SurfaceWithFewOutliersIsExact) {
    const auto p = test_points(20, 1);  // The outliers take the linear-scan fallback.
    const NeighborGraph graph = build_neighbor_graph(p, {.k_neighbors = 15});
    EXPECT_GE(graph.num_exact_fallbacks, 20u);
    EXPECT_LE(graph.num_exact_fallbacks, 256u);
    expect_exact(p, 15, 0.0f);
}

TEST(NeighborGraph, ManyOutliersStayExact) { expect_exact(test_points(600, 2), 15, 0.0f); }

TEST(NeighborGraph, RadiusLimitAndOtherKAreExact) {
    expect_exact(test_points(20, 3), 8, 0.002f);
    expect_exact(test_points(5, 4), 30, 0.0f);
}

// A 1 mm lattice next to a 6 mm one, both flat: equal distances everywhere (ties go by
// index) and a sparse part whose k-th neighbours lie beyond the 3x3x3 block of cells sized
// for the dense part, answered by the wider blocks.
TEST(NeighborGraph, LatticeTiesAndADensityStepAreExact) {
    std::vector<Eigen::Vector3f> p;
    for (int i = 0; i < 40; ++i) {
        for (int j = 0; j < 40; ++j) p.emplace_back(0.001f * float(i), 0.001f * float(j), 0.0f);
    }
    const std::size_t sparse = 12 * 12;
    for (std::size_t i = 0; i < sparse; ++i) {
        p.emplace_back(0.045f + 0.006f * float(i / 12), 0.006f * float(i % 12), 0.0f);
    }
    const NeighborGraph graph = build_neighbor_graph(p, {.k_neighbors = 15});
    EXPECT_LT(graph.num_exact_fallbacks, sparse / 2);
    expect_exact(p, 15, 0.0f);
    expect_exact(p, 15, 0.0035f);
}

}  // namespace
}  // namespace anascan
