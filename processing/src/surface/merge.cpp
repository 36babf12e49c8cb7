#include "merge.hpp"

#include <algorithm>
#include <cmath>

#include "anascan/processing/cleaning/normals.hpp"
#include "anascan/processing/core/median.hpp"
#include "anascan/processing/spatial/kdtree.hpp"

namespace anascan::surface_detail {
namespace {

constexpr std::int64_t kHalfRange = std::int64_t(1) << 20;  // 21 bits per axis

struct Keyed {
    std::uint64_t key = 0;
    std::uint32_t scan = 0;
    Eigen::Vector3f p;
};

// Packs the cell of p; false when outside the grid's range.
bool cell_key(const Eigen::Vector3f& p, double inv_cell, std::uint64_t& key) {
    std::uint64_t out = 0;
    for (int a = 0; a < 3; ++a) {
        const std::int64_t c = static_cast<std::int64_t>(std::floor(p[a] * inv_cell)) + kHalfRange;
        if (c < 0 || c >= 2 * kHalfRange) return false;
        out = (out << 21) | static_cast<std::uint64_t>(c);
    }
    key = out;
    return true;
}

std::vector<Keyed> keyed_points(std::span<const PlacedScan> scans, const Eigen::Vector3d& origin,
                                double cell_m, bool& too_large) {
    std::vector<Keyed> all;
    std::size_t total = 0;
    for (const PlacedScan& s : scans) total += s.cloud->size();
    all.reserve(total);
    const double inv_cell = 1.0 / cell_m;
    for (std::uint32_t si = 0; si < scans.size(); ++si) {
        const PointCloud& c = *scans[si].cloud;
        const Eigen::Vector3f shift = (c.origin_m - origin).cast<float>();
        for (const Eigen::Vector3f& q : c.positions) {
            if (!q.allFinite()) continue;
            Keyed k{.scan = si, .p = q + shift};
            if (!cell_key(k.p, inv_cell, k.key)) {
                too_large = true;
                continue;
            }
            all.push_back(k);
        }
    }
    std::stable_sort(all.begin(), all.end(),
                     [](const Keyed& a, const Keyed& b) { return a.key < b.key; });
    return all;
}

void find_isolated(MergedCloud& m, std::size_t scan_count,
                   const std::vector<std::uint32_t>& shared_cells) {
    if (scan_count < 2) return;
    for (std::size_t s = 0; s < scan_count; ++s) {
        if (shared_cells[s] == 0) m.isolated_scans.push_back(s);
    }
}

}  // namespace

MergedCloud merge_scans(std::span<const PlacedScan> scans, double cell_m) {
    MergedCloud m;
    if (scans.empty()) return m;
    m.cloud.origin_m = scans.front().cloud->origin_m;
    const std::vector<Keyed> all =
        keyed_points(scans, m.cloud.origin_m, cell_m, m.extent_too_large);
    m.input_points = all.size();
    std::vector<std::uint32_t> shared_cells(scans.size(), 0);
    for (std::size_t i = 0; i < all.size();) {
        std::size_t j = i;
        Eigen::Vector3d sum = Eigen::Vector3d::Zero();
        std::uint16_t distinct = 0;
        std::uint32_t last = UINT32_MAX, first = UINT32_MAX;
        for (; j < all.size() && all[j].key == all[i].key; ++j) {
            sum += all[j].p.cast<double>();
            if (all[j].scan != last) ++distinct;
            last = all[j].scan;
            first = std::min(first, all[j].scan);
        }
        if (distinct > 1) {
            for (std::size_t k = i; k < j; ++k) ++shared_cells[all[k].scan];
        }
        m.cloud.positions.push_back((sum / double(j - i)).cast<float>());
        m.scans.push_back(distinct);
        m.first_scan.push_back(first);
        i = j;
    }
    find_isolated(m, scans.size(), shared_cells);
    return m;
}

std::size_t orient_merged_normals(MergedCloud& merged, std::span<const PlacedScan> scans,
                                  int k_neighbors) {
    PointCloud& cloud = merged.cloud;
    const NormalEstimationResult est =
        estimate_normals(cloud, {.k_neighbors = k_neighbors, .keep_graph = true});
    bool any_unknown = false, any_known = false;
    for (const PlacedScan& s : scans) (s.sensor_world_m ? any_known : any_unknown) = true;
    if (any_unknown) orient_consistently(cloud, est.graph);
    // Sign agreement of the consistent orientation with the known sensors.
    std::ptrdiff_t agree = 0;
    for (std::size_t i = 0; i < cloud.size(); ++i) {
        const auto& sensor = scans[merged.first_scan[i]].sensor_world_m;
        if (!sensor) continue;
        const Eigen::Vector3f to_sensor = (*sensor - cloud.world_position(i)).cast<float>();
        const float d = cloud.normals[i].dot(to_sensor);
        if (!any_unknown) {
            if (d < 0) cloud.normals[i] = -cloud.normals[i];
        } else {
            agree += d >= 0 ? 1 : -1;
        }
    }
    if (any_unknown && any_known && agree < 0) {
        for (Eigen::Vector3f& n : cloud.normals) n = -n;
    }
    return est.num_too_few_neighbors + est.num_degenerate;
}

double median_spacing(const PointCloud& cloud) {
    if (cloud.size() < 2) return 0.0;
    const KdTree tree(cloud.positions);
    const std::size_t step = std::max<std::size_t>(1, cloud.size() / 20000);
    std::vector<double> d;
    std::vector<Neighbor> nn;
    for (std::size_t i = 0; i < cloud.size(); i += step) {
        tree.knn(cloud.positions[i], 2, nn);
        if (nn.size() == 2) d.push_back(std::sqrt(double(nn[1].distance_sq_m2)));
    }
    return upper_median(std::move(d));
}

}  // namespace anascan::surface_detail
