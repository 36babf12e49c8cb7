// Holes below a face (paper §5.1): clusters of points well below the face's plane whose
// normals face the same way (hole floors; chip fractures and the neighbouring faces lean
// away), clustered on a grid in the face's plane, typed by their outline.
#include <algorithm>
#include <cmath>
#include <numeric>
#include <unordered_map>

#include "cgal_geometry.hpp"
#include "feature_steps.hpp"

namespace anascan::reassembly::detail {
namespace {

// Union-find over the occupied cells of a 2-D grid.
struct Clusters {
    std::vector<int> parent;
    int find(int i) { return parent[i] == i ? i : parent[i] = find(parent[i]); }
    void join(int a, int b) { parent[find(a)] = find(b); }
};

std::int64_t cell_key(std::int64_t x, std::int64_t y) { return x * 1000003 + y; }

// Floor points of the face's holes as (u, v) in the face frame, with their depths.
struct FloorPoints {
    std::vector<Eigen::Vector2d> uv;
    std::vector<double> depth_m;
};

FloorPoints floor_points(const FeatureInput& in, const PlanarFace& f, const HoleConfig& c) {
    FloorPoints out;
    for (std::size_t i = 0; i < in.points.size(); ++i) {
        const Eigen::Vector3d p = in.points[i].cast<double>();
        const double depth = f.offset_m - f.normal.dot(p);
        if (depth < c.min_depth_m || depth > c.max_depth_m) continue;
        if (f.normal.dot(in.normals[i].cast<double>()) < c.floor_cos) continue;
        const Eigen::Vector2d uv = face_uv(f, p);
        if (std::abs(uv.x()) > 0.5 * f.width_m || std::abs(uv.y()) > 0.5 * f.height_m) continue;
        out.uv.push_back(uv);
        out.depth_m.push_back(depth);
    }
    return out;
}

// Cluster label of every floor point: grid cells of `cell_m`, joined with their 8 neighbours.
std::vector<int> cluster_labels(const FloorPoints& floor, double cell_m) {
    std::unordered_map<std::int64_t, int> cell_of;
    std::vector<int> point_cell(floor.uv.size());
    std::vector<std::pair<std::int64_t, std::int64_t>> cells;
    for (std::size_t i = 0; i < floor.uv.size(); ++i) {
        const auto x = static_cast<std::int64_t>(std::floor(floor.uv[i].x() / cell_m));
        const auto y = static_cast<std::int64_t>(std::floor(floor.uv[i].y() / cell_m));
        auto [it, inserted] = cell_of.try_emplace(cell_key(x, y), int(cells.size()));
        if (inserted) cells.emplace_back(x, y);
        point_cell[i] = it->second;
    }
    Clusters uf{std::vector<int>(cells.size())};
    std::iota(uf.parent.begin(), uf.parent.end(), 0);
    for (std::size_t c = 0; c < cells.size(); ++c)
        for (int dx = -1; dx <= 1; ++dx)
            for (int dy = -1; dy <= 1; ++dy)
                if (auto it = cell_of.find(cell_key(cells[c].first + dx, cells[c].second + dy));
                    it != cell_of.end())
                    uf.join(int(c), it->second);
    std::vector<int> labels(floor.uv.size());
    for (std::size_t i = 0; i < labels.size(); ++i) labels[i] = uf.find(point_cell[i]);
    return labels;
}

}  // namespace

void face_holes(const FeatureInput& in, std::vector<FaceBuild>& faces, const HoleConfig& c) {
    const double cell_m = 2.5 * in.spacing_m;
    for (FaceBuild& fb : faces) {
        PlanarFace& f = fb.face;
        const FloorPoints floor = floor_points(in, f, c);
        const std::vector<int> labels = cluster_labels(floor, cell_m);
        std::unordered_map<int, std::vector<std::size_t>> members;
        for (std::size_t i = 0; i < labels.size(); ++i) members[labels[i]].push_back(i);
        for (const auto& [label, idx] : members) {
            if (double(idx.size()) * in.spacing_m * in.spacing_m < c.min_area_m2) continue;
            std::vector<Eigen::Vector2d> uv;
            double depth_m = 0.0;
            for (std::size_t i : idx)
                uv.push_back(floor.uv[i]), depth_m = std::max(depth_m, floor.depth_m[i]);
            const Rectangle2 r = min_area_rectangle(uv);
            FaceHole hole{.face_uv_m = r.centre,
                          .length_m = r.long_m + in.spacing_m,
                          .width_m = r.short_m + in.spacing_m,
                          .depth_m = depth_m};
            hole.kind = hole.length_m > c.clamp_aspect * hole.width_m ? HoleKind::kClampChannel
                                                                      : HoleKind::kDowel;
            hole.centre_m = f.centre_m + r.centre.x() * f.width_axis + r.centre.y() * f.height_axis;
            f.holes.push_back(hole);
        }
        std::sort(f.holes.begin(), f.holes.end(), [](const FaceHole& a, const FaceHole& b) {
            return a.face_uv_m.x() < b.face_uv_m.x();
        });
    }
}

}  // namespace anascan::reassembly::detail
