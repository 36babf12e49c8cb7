#include "anascan/acquisition/store/session_truth.hpp"

#include "anascan/acquisition/store/groups.hpp"

namespace anascan::acquisition {
namespace {

Eigen::Vector3d centroid(const PointCloud& cloud) {
    Eigen::Vector3d sum = Eigen::Vector3d::Zero();
    std::size_t n = 0;
    for (const Eigen::Vector3f& p : cloud.positions)
        if (p.allFinite()) sum += p.cast<double>(), ++n;
    return n > 0 ? Eigen::Vector3d(sum / static_cast<double>(n) + cloud.origin_m)
                 : Eigen::Vector3d(cloud.origin_m);
}

}  // namespace

Expected<std::optional<PoseEvaluation>> evaluate_session_truth(const SessionStore& store) {
    auto scans = store.scans();
    if (!scans) return fail(scans.error());
    const int group = largest_group(*scans);
    std::vector<NamedPose> estimated, truth;
    for (const ScanRecord& s : *scans) {
        if (!s.true_pose || s.excluded) continue;
        const std::string name = std::to_string(s.seq);
        NamedPose t{.name = name, .T_world_scan = *s.true_pose};
        if (counts_in_group(s) && s.group == group) {
            estimated.push_back({.name = name, .T_world_scan = *s.pose});
            auto scan = store.load_scan(s.seq);
            if (!scan) return fail(scan.error());
            t.measure_at_scan_m = centroid(scan->cloud);
        }
        truth.push_back(t);
    }
    if (estimated.empty()) return std::optional<PoseEvaluation>();
    return evaluate_poses(estimated, truth);
}

}  // namespace anascan::acquisition
