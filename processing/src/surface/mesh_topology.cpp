#include "anascan/processing/surface/mesh_topology.hpp"

#include <algorithm>
#include <cstdint>
#include <numeric>
#include <unordered_map>

namespace anascan {
namespace {

struct HalfEdge {
    int from = 0, to = 0, triangle = 0;
    std::uint64_t edge = 0;  ///< The undirected edge: (min vertex) << 32 | (max vertex).
};

// Half-edges sorted by their undirected edge, so that each edge's uses are adjacent.
std::vector<HalfEdge> sorted_half_edges(const Mesh& mesh) {
    std::vector<HalfEdge> h;
    h.reserve(mesh.triangles.size() * 3);
    for (int t = 0; t < static_cast<int>(mesh.triangles.size()); ++t) {
        const Eigen::Vector3i& tri = mesh.triangles[t];
        for (int k = 0; k < 3; ++k) {
            const int a = tri[k], b = tri[(k + 1) % 3];
            const auto lo = std::uint64_t(std::uint32_t(std::min(a, b)));
            const auto hi = std::uint64_t(std::uint32_t(std::max(a, b)));
            h.push_back({a, b, t, lo << 32 | hi});
        }
    }
    std::sort(h.begin(), h.end(), [](const HalfEdge& a, const HalfEdge& b) {
        return a.edge != b.edge ? a.edge < b.edge : a.triangle < b.triangle;
    });
    return h;
}

int find_root(std::vector<int>& parent, int i) {
    while (parent[i] != i) i = parent[i] = parent[parent[i]];
    return i;
}

void label_components(const std::vector<int>& root_of_triangle, MeshTopology& topo) {
    std::unordered_map<int, int> size;
    for (const int r : root_of_triangle) ++size[r];
    std::vector<std::pair<int, int>> order(size.begin(), size.end());
    std::sort(order.begin(), order.end(), [](const auto& a, const auto& b) {
        return a.second != b.second ? a.second > b.second : a.first < b.first;
    });
    std::unordered_map<int, int> label;
    for (std::size_t i = 0; i < order.size(); ++i) label[order[i].first] = static_cast<int>(i);
    topo.components = order.size();
    topo.triangle_component.resize(root_of_triangle.size());
    for (std::size_t t = 0; t < root_of_triangle.size(); ++t) {
        topo.triangle_component[t] = label[root_of_triangle[t]];
    }
}

// Follows boundary half-edges (from -> to) into loops; a vertex with several outgoing
// boundary edges (a pinch) is left where the walk cannot continue.
void trace_loops(const std::vector<HalfEdge>& boundary, MeshTopology& topo) {
    std::unordered_multimap<int, std::size_t> out;
    for (std::size_t i = 0; i < boundary.size(); ++i) out.emplace(boundary[i].from, i);
    std::vector<bool> used(boundary.size(), false);
    for (std::size_t start = 0; start < boundary.size(); ++start) {
        if (used[start]) continue;
        std::vector<int> loop;
        std::size_t e = start;
        while (!used[e]) {
            used[e] = true;
            loop.push_back(boundary[e].from);
            const auto [lo, hi] = out.equal_range(boundary[e].to);
            auto next = std::find_if(lo, hi, [&](const auto& kv) { return !used[kv.second]; });
            if (next == hi) break;
            e = next->second;
        }
        topo.boundary_loops.push_back(std::move(loop));
    }
}

std::size_t count_fan_breaks(const Mesh& mesh, const std::vector<HalfEdge>& h) {
    // Around each vertex, triangles sharing an edge through it are joined; more than one
    // group means several fans meet at the vertex.
    std::vector<int> parent(mesh.triangles.size() * 3);
    std::iota(parent.begin(), parent.end(), 0);
    const auto corner = [&](int t, int v) {
        const Eigen::Vector3i& tri = mesh.triangles[t];
        return 3 * t + (tri[0] == v ? 0 : tri[1] == v ? 1 : 2);
    };
    for (std::size_t i = 0; i + 1 < h.size(); ++i) {
        const HalfEdge& a = h[i];
        const HalfEdge& b = h[i + 1];
        if (std::minmax(a.from, a.to) != std::minmax(b.from, b.to)) continue;
        for (const int v : {a.from, a.to}) {
            parent[find_root(parent, corner(a.triangle, v))] =
                find_root(parent, corner(b.triangle, v));
        }
    }
    std::vector<int> groups(mesh.vertices.size(), 0);
    for (int c = 0; c < static_cast<int>(parent.size()); ++c) {
        if (find_root(parent, c) == c) ++groups[mesh.triangles[c / 3][c % 3]];
    }
    return static_cast<std::size_t>(
        std::count_if(groups.begin(), groups.end(), [](int g) { return g > 1; }));
}

}  // namespace

MeshTopology analyse_topology(const Mesh& mesh) {
    MeshTopology topo;
    const std::vector<HalfEdge> h = sorted_half_edges(mesh);
    std::vector<int> parent(mesh.triangles.size());
    std::iota(parent.begin(), parent.end(), 0);
    std::vector<HalfEdge> boundary;
    for (std::size_t i = 0; i < h.size();) {
        const HalfEdge& first = h[i];
        std::size_t uses = 1;
        bool same_direction = false;
        for (++i; i < h.size() && h[i].edge == first.edge; ++i, ++uses) {
            same_direction = same_direction || h[i].from == first.from;
            parent[find_root(parent, h[i].triangle)] = find_root(parent, first.triangle);
        }
        if (uses == 1) boundary.push_back(first);
        if (uses > 2) ++topo.non_manifold_edges;
        if (uses == 2 && same_direction) ++topo.inconsistent_edges;
    }
    topo.boundary_edges = boundary.size();
    std::vector<int> roots(mesh.triangles.size());
    for (std::size_t t = 0; t < roots.size(); ++t) roots[t] = find_root(parent, int(t));
    label_components(roots, topo);
    topo.non_manifold_vertices = count_fan_breaks(mesh, h);
    trace_loops(boundary, topo);
    return topo;
}

}  // namespace anascan
