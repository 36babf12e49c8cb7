#include "anascan/acquisition/session_coverage.hpp"

#include <map>
#include <nlohmann/json.hpp>

#include "anascan/processing/voxel_grid.hpp"

namespace anascan::acquisition {
namespace {

/// The group with the most registered, non-excluded scans (lowest id on a tie); -1: none.
int largest_group(const std::vector<ScanRecord>& scans) {
    std::map<int, std::size_t> sizes;
    for (const ScanRecord& s : scans)
        if (s.state == ScanState::kRegistered && !s.excluded && s.pose) ++sizes[s.group];
    int best = -1;
    std::size_t best_size = 0;
    for (const auto& [group, size] : sizes)
        if (size > best_size) best = group, best_size = size;
    return best;
}

}  // namespace

Expected<CoverageReport> session_coverage(
    const SessionStore& store, const SessionCoverageConfig& config,
    const std::function<void(std::size_t, std::size_t)>& progress) {
    auto scans = store.scans();
    if (!scans) return fail(scans.error());
    const int group = largest_group(*scans);
    if (group < 0)
        return fail(ErrorCode::kEmpty, store.dir().string() + ": no registered scan to cover");
    std::vector<PointCloud> clouds;
    std::vector<CoverageScanView> views;
    std::vector<const ScanRecord*> members;
    for (const ScanRecord& s : *scans)
        if (s.state == ScanState::kRegistered && !s.excluded && s.pose && s.group == group)
            members.push_back(&s);
    clouds.reserve(members.size());
    for (std::size_t i = 0; i < members.size(); ++i) {
        auto scan = store.load_scan(members[i]->seq);
        if (!scan) return fail(scan.error());
        clouds.push_back(voxel_downsample(scan->cloud, {.voxel_size_m = config.voxel_size_m}));
        views.push_back({.cloud = &clouds.back(),
                         .T_world_scan = *members[i]->pose,
                         .sensor_origin_scan_m = scan->meta.sensor_origin_scan_m});
        if (progress) progress(i + 1, members.size());
    }
    return compute_coverage(views, config.coverage);
}

nlohmann::json coverage_json(const CoverageReport& report) {
    nlohmann::json holes = nlohmann::json::array();
    for (const CoverageHole& h : report.holes)
        holes.push_back({{"area_m2", h.area_m2},
                         {"centre_m", {h.centre_m.x(), h.centre_m.y(), h.centre_m.z()}},
                         {"normal", {h.normal.x(), h.normal.y(), h.normal.z()}},
                         {"samples", h.sample_count}});
    return {{"fraction", report.fraction},
            {"surface_area_m2", report.surface_area_m2},
            {"covered_area_m2", report.covered_area_m2},
            {"holes", holes}};
}

}  // namespace anascan::acquisition
