// register_scans: prepare → pairwise global registration → pose graph → links → multi-view.
#include "anascan/processing/scan_registration.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <string>
#include <utility>

#include "anascan/processing/voxel_grid.hpp"
#include "scan_registration_steps.hpp"

namespace anascan {
namespace detail {

double seconds_since(std::chrono::steady_clock::time_point start) {
    return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

}  // namespace detail

namespace {

using detail::seconds_since;

void report(const RegistrationProgress& progress, const std::string& message) {
    if (progress) progress(message);
}

/// Keeps the points whose normal is finite and of unit length (zero = not estimated).
void drop_points_without_normal(PointCloud& cloud) {
    std::vector<std::size_t> keep;
    keep.reserve(cloud.size());
    for (std::size_t i = 0; i < cloud.size(); ++i) {
        const Eigen::Vector3f& n = cloud.normals[i];
        if (n.allFinite() && std::abs(n.squaredNorm() - 1.0f) < 1e-3f) keep.push_back(i);
    }
    if (keep.size() != cloud.size()) cloud = select(cloud, keep);
}

/// Loads and prepares every scan (one full cloud in memory at a time); fills the outcomes.
std::vector<PointCloud> load_and_prepare(const std::vector<ScanInput>& inputs,
                                         const ScanRegistrationConfig& config,
                                         const RegistrationProgress& progress,
                                         ScanRegistrationResult& result) {
    std::vector<PointCloud> clouds(inputs.size());
    for (std::size_t i = 0; i < inputs.size(); ++i) {
        ScanOutcome& scan = result.scans[i];
        report(progress, "preparing " + inputs[i].name);
        Expected<PointCloud> loaded =
            inputs[i].load ? inputs[i].load() : Expected<PointCloud>(PointCloud{});
        if (!loaded) {
            scan.reason = "could not be loaded: " + loaded.error().message;
            continue;
        }
        scan.normals_estimated = !loaded->has_normals();
        scan.point_count = prepare_scan(*loaded, inputs[i].sensor_origin_scan_m, config);
        if (scan.point_count == 0) {
            scan.reason = "empty scan (no finite points with a normal)";
            continue;
        }
        clouds[i] = std::move(*loaded);
    }
    return clouds;
}

/// Weight of a verified pair in the maximum spanning tree (higher is better).
double pair_weight(const GlobalRegistrationResult& global) {
    const double spacing = std::max(global.target_spacing_m, 1e-9);
    return global.overlap_fraction / (1.0 + global.rms_m / spacing);
}

/// Global registration of every pair of usable scans: source = the later scan.
std::vector<PairOutcome> register_all_pairs(const std::vector<PointCloud>& clouds,
                                            const std::vector<bool>& usable,
                                            const ScanRegistrationConfig& config,
                                            const RegistrationProgress& progress) {
    std::vector<PairOutcome> pairs;
    const std::size_t n = clouds.size();
    const std::size_t total = n * (n - 1) / 2;
    for (std::size_t source = 1; source < n; ++source) {
        for (std::size_t target = 0; target < source; ++target) {
            PairOutcome pair{.source = source, .target = target};
            if (usable[source] && usable[target]) {
                const GlobalRegistrationResult g =
                    register_global(clouds[source], clouds[target], config.global);
                pair.global_status = g.status;
                pair.verified = g.status == GlobalRegistrationStatus::kSuccess;
                pair.weight = pair.verified ? pair_weight(g) : 0.0;
                pair.T_target_source = g.T_target_source;
                pair.global_rms_m = g.rms_m;
                pair.global_overlap_fraction = g.overlap_fraction;
                pair.global_time_s = g.timing.total_s;
            }
            pairs.push_back(pair);
            report(progress, "global registration " + std::to_string(pairs.size()) + " of " +
                                 std::to_string(total) + ": scan " + std::to_string(source) +
                                 " onto " + std::to_string(target) + ": " +
                                 std::string(to_string(pair.global_status)));
        }
    }
    return pairs;
}

/// Copies the graph's groups and poses into the outcomes and counts.
void place_scans(const detail::PoseGraph& graph, ScanRegistrationResult& result) {
    bool reference_found = false;
    for (std::size_t i = 0; i < result.scans.size(); ++i) {
        ScanOutcome& scan = result.scans[i];
        scan.group = graph.group[i];
        if (scan.group < 0) continue;
        scan.T_world_scan = graph.T_root_scan[i];
        scan.placed = scan.group == 0;
        if (!scan.placed) {
            scan.reason = "no verified chain of pairs to the largest group (in group " +
                          std::to_string(scan.group) + ")";
        }
        if (scan.placed && !reference_found) {
            result.reference_scan = i;
            reference_found = true;
        }
        result.placed_count += scan.placed;
    }
    result.group_count = graph.group_count;
}

}  // namespace

std::size_t prepare_scan(PointCloud& cloud, const std::optional<Eigen::Vector3d>& sensor_origin_m,
                         const ScanRegistrationConfig& config) {
    remove_non_finite(cloud);
    if (cloud.empty()) return 0;
    if (!cloud.has_normals()) {
        NormalEstimationResult estimated = estimate_normals(cloud, config.normals);
        if (sensor_origin_m) {
            orient_toward(cloud, (*sensor_origin_m - cloud.origin_m).cast<float>());
        } else {
            orient_consistently(cloud, estimated.graph);
        }
    }
    drop_points_without_normal(cloud);
    if (config.voxel_size_m > 0.0 && !cloud.empty()) {
        cloud = voxel_downsample(cloud, {.voxel_size_m = config.voxel_size_m});
    }
    return cloud.size();
}

ScanRegistrationResult register_scans(const std::vector<ScanInput>& scans,
                                      const ScanRegistrationConfig& config,
                                      const RegistrationProgress& progress) {
    const auto start = std::chrono::steady_clock::now();
    ScanRegistrationResult result;
    for (const ScanInput& input : scans) result.scans.push_back({.name = input.name});
    auto stage = std::chrono::steady_clock::now();
    const std::vector<PointCloud> clouds = load_and_prepare(scans, config, progress, result);
    std::vector<bool> usable(scans.size());
    for (std::size_t i = 0; i < scans.size(); ++i) usable[i] = !clouds[i].empty();
    result.timings.prepare_s = seconds_since(stage);

    stage = std::chrono::steady_clock::now();
    result.pairs = register_all_pairs(clouds, usable, config, progress);
    for (const PairOutcome& p : result.pairs) result.verified_pair_count += p.verified;
    result.timings.pairwise_s = seconds_since(stage);

    stage = std::chrono::steady_clock::now();
    detail::PoseGraph graph = detail::build_pose_graph(usable, result.pairs);
    result.timings.pose_graph_s = seconds_since(stage);

    stage = std::chrono::steady_clock::now();
    const detail::PairLinks links =
        detail::make_links(clouds, graph, result.pairs, config, progress);
    result.link_count = links.links.size();
    result.timings.fine_s = seconds_since(stage);

    stage = std::chrono::steady_clock::now();
    report(progress, "multi-view refinement over " + std::to_string(result.link_count) + " links");
    result.multiview_status = detail::refine_groups(links, config.multiview, graph, result.pairs);
    for (const PairOutcome& p : result.pairs) result.dropped_link_count += p.link_dropped;
    result.timings.multiview_s = seconds_since(stage);

    place_scans(graph, result);
    result.timings.total_s = seconds_since(start);
    return result;
}

}  // namespace anascan
