// union_pulls: each scan of a group registered against all the others at once.
#include "anascan/processing/evaluation/union_pull.hpp"

#include <algorithm>
#include <cmath>

#include "anascan/processing/spatial/kdtree.hpp"

namespace anascan {
namespace {

/// The scans other than `skip`, in the group frame, as one cloud (positions and normals).
PointCloud others_in_group(std::span<const ConsistencyScan> scans, std::size_t skip) {
    PointCloud out;
    for (std::size_t k = 0; k < scans.size(); ++k) {
        if (k == skip) continue;
        const PointCloud& cloud = *scans[k].cloud;
        const Pose T = scans[k].T_group_scan * Eigen::Translation3d(cloud.origin_m);
        const Eigen::Matrix3f R = T.linear().cast<float>();
        const Eigen::Vector3f t = T.translation().cast<float>();
        for (std::size_t i = 0; i < cloud.size(); ++i) {
            out.positions.push_back(R * cloud.positions[i] + t);
            out.normals.push_back(cloud.has_normals() ? Eigen::Vector3f(R * cloud.normals[i])
                                                      : Eigen::Vector3f::Zero());
        }
    }
    return out;
}

Eigen::Vector3d centroid_in_scan(const PointCloud& cloud) {
    Eigen::Vector3d sum = Eigen::Vector3d::Zero();
    for (const Eigen::Vector3f& p : cloud.positions) sum += p.cast<double>();
    return cloud.origin_m + sum / static_cast<double>(std::max<std::size_t>(1, cloud.size()));
}

/// RMS point-to-plane residual and overlap of `source` placed by T on the target, over the
/// source points within `gate_m` of a target point (every `stride`-th point).
struct Fit {
    double rms_m = 0.0;
    double overlap_fraction = 0.0;
};

Fit fit_at(const PointCloud& source, const PointCloud& target, const KdTree& tree, const Pose& T,
           double gate_m) {
    const std::size_t stride = std::max<std::size_t>(1, source.size() / 20000);
    std::vector<Neighbor> nearest;
    double sum_sq = 0.0;
    std::size_t near = 0, tried = 0;
    for (std::size_t i = 0; i < source.size(); i += stride, ++tried) {
        const Eigen::Vector3d p = T * (source.origin_m + source.positions[i].cast<double>());
        tree.knn(p.cast<float>(), 1, nearest);
        if (nearest.empty()) continue;
        const Eigen::Vector3f q = target.positions[nearest[0].index];
        if ((p.cast<float>() - q).norm() > gate_m) continue;
        const double r = target.normals[nearest[0].index].dot(p.cast<float>() - q);
        sum_sq += r * r;
        ++near;
    }
    if (near == 0) return {};
    return {.rms_m = std::sqrt(sum_sq / static_cast<double>(near)),
            .overlap_fraction = static_cast<double>(near) / static_cast<double>(tried)};
}

ScanPull pull_of(std::span<const ConsistencyScan> scans, std::size_t i,
                 const UnionPullConfig& config) {
    ScanPull out;
    const PointCloud target = others_in_group(scans, i);
    if (target.empty() || scans[i].cloud->empty()) return out;
    const KdTree tree(target.positions);
    const Pose T_start = scans[i].T_group_scan;
    const Eigen::Vector3d centroid = centroid_in_scan(*scans[i].cloud);
    Pose T = T_start;
    FineRegistrationResult fine;
    for (out.rounds = 1; out.rounds <= config.max_rounds; ++out.rounds) {
        fine = register_fine(*scans[i].cloud, target, tree, T, config.fine);
        if (fine.status != FineRegistrationStatus::kConverged &&
            fine.status != FineRegistrationStatus::kMaxIterations)
            return out;
        const double step_m = (fine.T_target_source * centroid - T * centroid).norm();
        T = fine.T_target_source;
        if (step_m < config.settle_m) break;
    }
    out.rounds = std::min(out.rounds, config.max_rounds);
    out.moved_m = (T * centroid - T_start * centroid).norm();
    out.rotation_deg = rotation_angle_deg(T_start.inverse() * T);
    const double gate_m = config.fine.overlap_distance_m;
    const Fit before = fit_at(*scans[i].cloud, target, tree, T_start, gate_m);
    const Fit after = fit_at(*scans[i].cloud, target, tree, T, gate_m);
    out.rms_before_m = before.rms_m;
    out.rms_m = after.rms_m;
    out.overlap_fraction = after.overlap_fraction;
    out.judged = after.overlap_fraction >= config.min_overlap_fraction;
    // A scan hanging off the group's edge can be dragged by the gate's first, wide
    // iterations: it fits worse where it ends, so only a move to a better fit counts.
    out.pulled = out.judged && out.moved_m > config.min_pull_m &&
                 out.moved_m > config.pull_rms_factor * after.rms_m && after.rms_m < before.rms_m;
    return out;
}

}  // namespace

std::vector<ScanPull> union_pulls(std::span<const ConsistencyScan> scans,
                                  const UnionPullConfig& config) {
    std::vector<ScanPull> out(scans.size());
    if (scans.size() < 3) return out;
    for (std::size_t i = 0; i < scans.size(); ++i) out[i] = pull_of(scans, i, config);
    return out;
}

}  // namespace anascan
