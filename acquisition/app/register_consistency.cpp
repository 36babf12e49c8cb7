#include "register_consistency.hpp"

#include <spdlog/spdlog.h>

#include <algorithm>
#include <cmath>
#include <cstdio>

#include "anascan/processing/cleaning/normals.hpp"
#include "anascan/processing/evaluation/group_consistency.hpp"
#include "anascan/processing/features/integral_invariants.hpp"
#include "anascan/processing/spatial/voxel_grid.hpp"

namespace anascan::cli {

PointCloud reduce_for_consistency(const PointCloud& cloud,
                                  const std::optional<Eigen::Vector3d>& sensor,
                                  std::size_t target_points) {
    const double spacing = median_sample_spacing_m(cloud);
    const double ratio = std::max(1.0, static_cast<double>(cloud.size()) / target_points);
    PointCloud out = spacing > 0.0
                         ? voxel_downsample(cloud, {.voxel_size_m = spacing * std::sqrt(ratio)})
                         : cloud;
    out.normals.clear();
    estimate_normals(out, {});
    if (sensor) orient_toward(out, (*sensor - out.origin_m).cast<float>());
    return out;
}

void print_pairs(const GroupConsistency& group, const std::vector<std::string>& names) {
    for (const PairConsistency& p : group.pairs)
        std::printf(
            "  %s - %s: near %zu, crossing %.1f %% (> %.1f°), median angle %.2f°, offset %.3f mm "
            "(noise %.3f mm), free space %.1f %% / %.1f %%: %s\n",
            names[p.a].c_str(), names[p.b].c_str(), p.near_samples, 100.0 * p.crossing_fraction,
            p.crossing_angle_deg, p.median_normal_angle_deg, p.median_offset_m * 1e3,
            p.noise_m * 1e3, 100.0 * p.b_seen_from_a.violation_fraction,
            100.0 * p.a_seen_from_b.violation_fraction, p.agrees ? "agrees" : p.reason.c_str());
}

RegisterConsistency check_placed_scans(ScanRegistrationResult& result,
                                       const std::function<Expected<PointCloud>(std::size_t)>& load,
                                       const std::optional<Eigen::Vector3d>& sensor_origin_scan_m,
                                       std::size_t target_points) {
    std::vector<std::size_t> placed;
    std::vector<PointCloud> clouds;
    for (std::size_t i = 0; i < result.scans.size(); ++i) {
        if (!result.scans[i].placed) continue;
        auto cloud = load(i);
        if (!cloud) {
            spdlog::warn("consistency check skips {}: {}", result.scans[i].name,
                         cloud.error().message);
            continue;
        }
        placed.push_back(i);
        clouds.push_back(reduce_for_consistency(*cloud, sensor_origin_scan_m, target_points));
    }
    std::vector<ConsistencyScan> scans;
    std::vector<std::string> names;
    for (std::size_t k = 0; k < placed.size(); ++k) {
        scans.push_back({.cloud = &clouds[k],
                         .T_group_scan = result.scans[placed[k]].T_world_scan,
                         .sensor_origin_scan_m = sensor_origin_scan_m});
        names.push_back(result.scans[placed[k]].name);
    }
    const GroupConsistency group = check_group_consistency(scans, {});
    for (std::size_t k : group.take_out) {
        ScanOutcome& s = result.scans[placed[k]];
        const auto& worst = group.scans[k].worst_pair;
        s.placed = false;
        s.reason = "contradicts the other placed scans (disagrees with " +
                   std::to_string(group.scans[k].disagreeing) + " of " +
                   std::to_string(group.scans[k].overlapping) + " overlapping): " +
                   (worst ? describe(group.pairs[*worst], names) : std::string("?"));
        --result.placed_count;
    }
    return {
        .checked = placed.size(), .pairs = group.pairs.size(), .taken_out = group.take_out.size()};
}

}  // namespace anascan::cli
