#include "anascan/acquisition/coverage/session_coverage.hpp"

#include "anascan/processing/core/stopwatch.hpp"
#include "anascan/processing/spatial/voxel_grid.hpp"

namespace anascan::acquisition {

CoverageCopy make_coverage_copy(const Scan& scan, double voxel_size_m) {
    CoverageCopy copy;
    copy.cloud = voxel_downsample(scan.cloud, {.voxel_size_m = voxel_size_m});
    if (!copy.cloud.empty())
        copy.points_per_point =
            static_cast<double>(scan.cloud.size()) / static_cast<double>(copy.cloud.size());
    copy.sensor_origin_scan_m = scan.meta.sensor_origin_scan_m;
    return copy;
}

Expected<CoverageReport> session_coverage(
    const SessionStore& store, const SessionCoverageConfig& config,
    const std::function<void(std::size_t, std::size_t)>& progress) {
    auto scans = store.scans();
    if (!scans) return fail(scans.error());
    const int group = largest_group(*scans);
    if (group < 0)
        return fail(ErrorCode::kEmpty, store.dir().string() + ": no registered scan to cover");
    std::vector<CoverageCopy> copies;
    std::vector<CoverageScanView> views;
    std::vector<const ScanRecord*> members;
    for (const ScanRecord& s : *scans)
        if (counts_in_group(s) && s.group == group) members.push_back(&s);
    copies.reserve(members.size());
    for (std::size_t i = 0; i < members.size(); ++i) {
        auto scan = store.load_scan(members[i]->seq);
        if (!scan) return fail(scan.error());
        copies.push_back(make_coverage_copy(*scan, config.voxel_size_m));
        views.push_back({.cloud = &copies.back().cloud,
                         .T_world_scan = *members[i]->pose,
                         .sensor_origin_scan_m = copies.back().sensor_origin_scan_m,
                         .points_per_point = copies.back().points_per_point});
        if (progress) progress(i + 1, members.size());
    }
    return compute_coverage(views, config.coverage);
}

ScannerEnvelope session_scanner_envelope(const SessionStore& store) {
    auto scans = store.scans();
    if (scans && !scans->empty() && scans->back().device_kind == DeviceKind::kTimeOfFlight)
        return terrestrial_envelope();
    return structured_light_envelope();
}

namespace {

// Scanners are held upright: a structured-light head's image y points down (OpenCV camera
// frame), a terrestrial station's z up. The mean over the model's scans, in the model frame.
std::optional<Eigen::Vector3d> scanners_up(const SessionStore& store) {
    auto scans = store.scans();
    if (!scans) return std::nullopt;
    const int group = largest_group(*scans);
    Eigen::Vector3d sum = Eigen::Vector3d::Zero();
    for (const ScanRecord& s : *scans) {
        if (!counts_in_group(s) || s.group != group || !s.pose) continue;
        if (s.device_kind == DeviceKind::kStructuredLight)
            sum += s.pose->linear() * -Eigen::Vector3d::UnitY();
        else if (s.device_kind == DeviceKind::kTimeOfFlight)
            sum += s.pose->linear() * Eigen::Vector3d::UnitZ();
    }
    if (sum.norm() < 1e-9) return std::nullopt;
    return sum.normalized();
}

// Sensor positions of the model's scans, model frame.
std::vector<Eigen::Vector3d> scanner_positions(const SessionStore& store) {
    std::vector<Eigen::Vector3d> out;
    auto scans = store.scans();
    if (!scans) return out;
    const int group = largest_group(*scans);
    for (const ScanRecord& s : *scans)
        if (counts_in_group(s) && s.group == group && s.pose)
            out.push_back(*s.pose * s.sensor_origin_scan_m.value_or(Eigen::Vector3d::Zero()));
    return out;
}

}  // namespace

Expected<SessionNextView> session_next_view(const SessionStore& store,
                                            const SessionCoverageConfig& coverage_config,
                                            NextViewConfig config, bool use_session_device) {
    auto coverage = session_coverage(store, coverage_config);
    if (!coverage) return fail(coverage.error());
    if (use_session_device) config.scanner = session_scanner_envelope(store);
    config.max_incidence_deg = coverage_config.coverage.max_incidence_deg;
    config.min_density_per_cm2 = coverage_config.coverage.min_density_per_cm2;
    if (!config.up_hint_world) config.up_hint_world = scanners_up(store);
    if (config.scanner_positions_world.empty())
        config.scanner_positions_world = scanner_positions(store);
    SessionNextView out;
    const Stopwatch watch;
    out.view = plan_next_view(*coverage, config);
    out.plan_s = watch.seconds();
    out.coverage = std::move(*coverage);
    return out;
}

Expected<std::optional<Pose>> group_to_truth(const SessionStore& store) {
    auto scans = store.scans();
    if (!scans) return fail(scans.error());
    const int group = largest_group(*scans);
    for (auto it = scans->rbegin(); it != scans->rend(); ++it)
        if (counts_in_group(*it) && it->group == group && it->pose && it->true_pose)
            return std::optional<Pose>(*it->true_pose * it->pose->inverse());
    return std::optional<Pose>();
}

}  // namespace anascan::acquisition
