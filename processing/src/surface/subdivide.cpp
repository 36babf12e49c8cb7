#include "subdivide.hpp"

#include <algorithm>
#include <cstdint>
#include <unordered_map>

namespace anascan::surface_detail {
namespace {

std::uint64_t edge_key(int a, int b) {
    const auto lo = std::uint64_t(std::uint32_t(std::min(a, b)));
    const auto hi = std::uint64_t(std::uint32_t(std::max(a, b)));
    return lo << 32 | hi;
}

}  // namespace

Mesh subdivide_midpoints(const Mesh& mesh) {
    Mesh out;
    out.vertices.origin_m = mesh.vertices.origin_m;
    out.vertices.positions = mesh.vertices.positions;
    const bool normals = mesh.vertices.normals.size() == mesh.vertices.size();
    if (normals) out.vertices.normals = mesh.vertices.normals;
    std::unordered_map<std::uint64_t, int> midpoint;
    midpoint.reserve(mesh.triangles.size() * 3 / 2);
    auto middle = [&](int a, int b) {
        auto [it, added] = midpoint.try_emplace(edge_key(a, b), int(out.vertices.size()));
        if (added) {
            auto& p = out.vertices.positions;
            const Eigen::Vector3f mid = 0.5f * (p[a] + p[b]);
            p.push_back(mid);
            if (normals) {
                auto& n = out.vertices.normals;
                Eigen::Vector3f sum = n[a] + n[b];
                if (sum.squaredNorm() > 0.0f) sum.normalize();
                n.push_back(sum);
            }
        }
        return it->second;
    };
    out.triangles.reserve(mesh.triangles.size() * 4);
    for (const Eigen::Vector3i& t : mesh.triangles) {
        const int ab = middle(t[0], t[1]), bc = middle(t[1], t[2]), ca = middle(t[2], t[0]);
        out.triangles.emplace_back(t[0], ab, ca);
        out.triangles.emplace_back(ab, t[1], bc);
        out.triangles.emplace_back(ca, bc, t[2]);
        out.triangles.emplace_back(ab, bc, ca);
    }
    return out;
}

}  // namespace anascan::surface_detail
