#include "anascan/processing/spatial/min_distance_sampling.hpp"

#include <array>
#include <cmath>
#include <unordered_map>

namespace anascan {
namespace {

using Cell = std::array<std::int64_t, 3>;

struct CellHash {
    std::size_t operator()(const Cell& c) const {
        return static_cast<std::size_t>(c[0] * 73856093 ^ c[1] * 19349663 ^ c[2] * 83492791);
    }
};

Cell cell_of(const Eigen::Vector3f& p, double size_m) {
    return {static_cast<std::int64_t>(std::floor(p.x() / size_m)),
            static_cast<std::int64_t>(std::floor(p.y() / size_m)),
            static_cast<std::int64_t>(std::floor(p.z() / size_m))};
}

using Cells = std::unordered_map<Cell, std::vector<std::uint32_t>, CellHash>;

/// Whether a kept point lies closer than the limit to p (in cell c or its 26 neighbours).
bool near_kept(const Cells& cells, const PointCloud& cloud, const Eigen::Vector3f& p, const Cell& c,
               float limit_sq) {
    for (int offset = 0; offset < 27; ++offset) {
        const Cell n{c[0] + offset % 3 - 1, c[1] + offset / 3 % 3 - 1, c[2] + offset / 9 - 1};
        const auto it = cells.find(n);
        if (it == cells.end()) continue;
        for (std::uint32_t j : it->second) {
            if ((cloud.positions[j] - p).squaredNorm() < limit_sq) return true;
        }
    }
    return false;
}

}  // namespace

std::vector<std::uint32_t> min_distance_sample(const PointCloud& cloud, double min_distance_m) {
    std::vector<std::uint32_t> kept;
    const bool all = !(min_distance_m > 0.0);
    const auto limit_sq = static_cast<float>(min_distance_m * min_distance_m);
    Cells cells;  // Cells of the minimum distance: closer points lie in the 27 around.
    for (std::uint32_t i = 0; i < cloud.size(); ++i) {
        const Eigen::Vector3f& p = cloud.positions[i];
        if (!p.allFinite()) continue;
        if (all) {
            kept.push_back(i);
            continue;
        }
        const Cell c = cell_of(p, min_distance_m);
        if (near_kept(cells, cloud, p, c, limit_sq)) continue;
        kept.push_back(i);
        cells[c].push_back(i);
    }
    return kept;
}

}  // namespace anascan
