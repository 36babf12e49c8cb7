// Consistent normal orientation without a sensor (Hoppe et al. 1992, §3.3): a minimum
// spanning forest of the neighbour graph under weights 1 - |n_i · n_j|, signs propagated
// along it, then one global sign per connected part.

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>
#include <tbb/parallel_sort.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <numeric>
#include <vector>

#include "anascan/processing/cleaning/normals.hpp"

namespace anascan {
namespace {

struct Edge {
    float weight = 0.0f;
    std::uint32_t a = 0, b = 0;  // a < b.
    friend bool operator<(const Edge& x, const Edge& y) {
        if (x.weight != y.weight) return x.weight < y.weight;
        return x.a != y.a ? x.a < y.a : x.b < y.b;
    }
};

bool has_normal(const PointCloud& cloud, std::size_t i) {
    return cloud.normals[i].allFinite() && !cloud.normals[i].isZero();
}

// Whether edge i -> j is the one copy kept of the undirected edge {i, j}.
bool owns_edge(const NeighborGraph& graph, std::uint32_t i, std::uint32_t j) {
    if (i < j) return true;
    const std::span<const std::uint32_t> back = graph.neighbors(j);
    return std::find(back.begin(), back.end(), i) == back.end();
}

// Undirected edges between points with normals, sorted by weight (ties by index: unique).
std::vector<Edge> weighted_edges(const PointCloud& cloud, const NeighborGraph& graph) {
    const std::size_t n = cloud.size();
    std::vector<std::size_t> offsets(n + 1, 0);
    auto for_owned = [&](std::uint32_t i, auto&& emit) {
        if (!has_normal(cloud, i)) return;
        for (const std::uint32_t j : graph.neighbors(i)) {
            if (j != i && has_normal(cloud, j) && owns_edge(graph, i, j)) emit(j);
        }
    };
    tbb::parallel_for(tbb::blocked_range<std::uint32_t>(0, std::uint32_t(n), 2048), [&](auto r) {
        for (std::uint32_t i = r.begin(); i < r.end(); ++i) {
            for_owned(i, [&](std::uint32_t) { ++offsets[i + 1]; });
        }
    });
    std::partial_sum(offsets.begin(), offsets.end(), offsets.begin());
    std::vector<Edge> edges(offsets[n]);
    tbb::parallel_for(tbb::blocked_range<std::uint32_t>(0, std::uint32_t(n), 2048), [&](auto r) {
        for (std::uint32_t i = r.begin(); i < r.end(); ++i) {
            std::size_t slot = offsets[i];
            for_owned(i, [&](std::uint32_t j) {
                const float w = 1.0f - std::abs(cloud.normals[i].dot(cloud.normals[j]));
                edges[slot++] = Edge{w, std::min(i, j), std::max(i, j)};
            });
        }
    });
    tbb::parallel_sort(edges.begin(), edges.end());
    return edges;
}

class DisjointSets {
public:
    explicit DisjointSets(std::size_t n) : parent_(n) {
        std::iota(parent_.begin(), parent_.end(), std::uint32_t(0));
    }
    std::uint32_t find(std::uint32_t x) {
        while (parent_[x] != x) x = parent_[x] = parent_[parent_[x]];  // Path halving.
        return x;
    }
    bool unite(std::uint32_t a, std::uint32_t b) {
        a = find(a);
        b = find(b);
        if (a == b) return false;
        parent_[std::max(a, b)] = std::min(a, b);  // Deterministic: smaller index is root.
        return true;
    }

private:
    std::vector<std::uint32_t> parent_;
};

// Kruskal: the minimum spanning forest as adjacency lists (CSR).
struct Forest {
    std::vector<std::size_t> begin;  // size n + 1
    std::vector<std::uint32_t> adjacent;
};

Forest spanning_forest(std::size_t n, const std::vector<Edge>& edges) {
    DisjointSets sets(n);
    std::vector<Edge> tree;
    for (const Edge& e : edges) {
        if (sets.unite(e.a, e.b)) tree.push_back(e);
    }
    Forest forest;
    forest.begin.assign(n + 1, 0);
    for (const Edge& e : tree) {
        ++forest.begin[e.a + 1];
        ++forest.begin[e.b + 1];
    }
    std::partial_sum(forest.begin.begin(), forest.begin.end(), forest.begin.begin());
    forest.adjacent.resize(2 * tree.size());
    std::vector<std::size_t> fill(forest.begin.begin(), forest.begin.end() - 1);
    for (const Edge& e : tree) {
        forest.adjacent[fill[e.a]++] = e.b;
        forest.adjacent[fill[e.b]++] = e.a;
    }
    return forest;
}

// Propagates signs over the tree containing `root`; returns its points in visit order.
std::vector<std::uint32_t> propagate(PointCloud& cloud, const Forest& forest, std::uint32_t root,
                                     std::vector<std::uint8_t>& visited) {
    std::vector<std::uint32_t> order{root};
    visited[root] = 1;
    for (std::size_t head = 0; head < order.size(); ++head) {
        const std::uint32_t i = order[head];
        for (std::size_t e = forest.begin[i]; e < forest.begin[i + 1]; ++e) {
            const std::uint32_t j = forest.adjacent[e];
            if (visited[j]) continue;
            visited[j] = 1;
            if (cloud.normals[j].dot(cloud.normals[i]) < 0.0f) cloud.normals[j] *= -1.0f;
            order.push_back(j);
        }
    }
    return order;
}

// Turns a whole part to point away from its centroid on average; +z when undecided.
void orient_part(PointCloud& cloud, const std::vector<std::uint32_t>& part) {
    Eigen::Vector3d centroid = Eigen::Vector3d::Zero();
    for (const std::uint32_t i : part) centroid += cloud.positions[i].cast<double>();
    centroid /= double(part.size());
    double outward = 0.0, spread = 0.0, up = 0.0;
    for (const std::uint32_t i : part) {
        const Eigen::Vector3d d = cloud.positions[i].cast<double>() - centroid;
        outward += cloud.normals[i].cast<double>().dot(d);
        spread += d.norm();
        up += cloud.normals[i].z();
    }
    const bool decided = std::abs(outward) > 1e-3 * spread;
    if ((decided && outward < 0.0) || (!decided && up < 0.0)) {
        for (const std::uint32_t i : part) cloud.normals[i] *= -1.0f;
    }
}

}  // namespace

OrientationResult orient_consistently(PointCloud& cloud, const NeighborGraph& graph) {
    OrientationResult result;
    const std::size_t n = cloud.size();
    if (cloud.normals.size() != n) return result;
    if (graph.size() != n) return orient_consistently(cloud, ConsistentOrientationConfig{});
    const std::vector<Eigen::Vector3f> before = cloud.normals;
    const Forest forest = spanning_forest(n, weighted_edges(cloud, graph));
    std::vector<std::uint8_t> visited(n, 0);
    for (std::uint32_t root = 0; root < n; ++root) {
        if (visited[root]) continue;
        if (!has_normal(cloud, root)) {
            ++result.num_unoriented;
            continue;
        }
        orient_part(cloud, propagate(cloud, forest, root, visited));
        ++result.num_components;
    }
    for (std::size_t i = 0; i < n; ++i) result.num_flipped += cloud.normals[i].dot(before[i]) < 0;
    return result;
}

}  // namespace anascan
