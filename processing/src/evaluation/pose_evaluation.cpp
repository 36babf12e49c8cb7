#include "anascan/processing/evaluation/pose_evaluation.hpp"

#include <Eigen/Geometry>
#include <algorithm>
#include <unordered_map>

namespace anascan {
namespace {

using PoseIndex = std::unordered_map<std::string, const NamedPose*>;

PoseIndex index_by_name(const std::vector<NamedPose>& poses) {
    PoseIndex index;
    for (const NamedPose& p : poses) index.emplace(p.name, &p);
    return index;
}

const NamedPose* first_common(const std::vector<NamedPose>& truth, const PoseIndex& estimated) {
    for (const NamedPose& t : truth) {
        if (estimated.contains(t.name)) return &t;
    }
    return nullptr;
}

// The maxima in the best-fit frame: estimated world → true world by the least-squares
// rigid motion of the measure points.
void add_best_fit(const std::vector<std::pair<const NamedPose*, const NamedPose*>>& pairs,
                  PoseEvaluation& eval) {
    eval.max_rotation_best_fit_deg = eval.max_rotation_deg;
    eval.max_translation_best_fit_m = eval.max_translation_m;
    if (pairs.size() < 3) return;
    Eigen::Matrix3Xd est(3, pairs.size()), truth(3, pairs.size());
    for (std::size_t i = 0; i < pairs.size(); ++i) {
        const auto& [e, t] = pairs[i];
        est.col(static_cast<Eigen::Index>(i)) = e->T_world_scan * t->measure_at_scan_m;
        truth.col(static_cast<Eigen::Index>(i)) = t->T_world_scan * t->measure_at_scan_m;
    }
    const Pose A(Eigen::umeyama(est, truth, false));
    eval.max_rotation_best_fit_deg = eval.max_translation_best_fit_m = 0.0;
    for (std::size_t i = 0; i < pairs.size(); ++i) {
        const auto& [e, t] = pairs[i];
        const Pose T_est = A * e->T_world_scan;
        eval.max_rotation_best_fit_deg = std::max(
            eval.max_rotation_best_fit_deg, pose_difference(t->T_world_scan, T_est).rotation_deg);
        eval.max_translation_best_fit_m = std::max(
            eval.max_translation_best_fit_m,
            (T_est * t->measure_at_scan_m - t->T_world_scan * t->measure_at_scan_m).norm());
    }
}

}  // namespace

std::optional<PoseEvaluation> evaluate_poses(const std::vector<NamedPose>& estimated,
                                             const std::vector<NamedPose>& truth) {
    const PoseIndex estimated_index = index_by_name(estimated);
    const PoseIndex truth_index = index_by_name(truth);
    const NamedPose* reference = first_common(truth, estimated_index);
    if (reference == nullptr) return std::nullopt;

    PoseEvaluation eval;
    eval.reference = reference->name;
    const Pose T_ref_world_truth = reference->T_world_scan.inverse();
    const Pose T_ref_world_est = estimated_index.at(reference->name)->T_world_scan.inverse();
    std::vector<std::pair<const NamedPose*, const NamedPose*>> pairs;  // (estimated, truth)
    for (const NamedPose& t : truth) {
        ScanPoseError error{.name = t.name};
        if (auto it = estimated_index.find(t.name); it != estimated_index.end()) {
            pairs.emplace_back(it->second, &t);
            const Pose T_ref_scan_truth = T_ref_world_truth * t.T_world_scan;
            const Pose T_ref_scan_est = T_ref_world_est * it->second->T_world_scan;
            const double rotation_deg =
                pose_difference(T_ref_scan_truth, T_ref_scan_est).rotation_deg;
            const double translation_m =
                (T_ref_scan_truth * t.measure_at_scan_m - T_ref_scan_est * t.measure_at_scan_m)
                    .norm();
            error = {t.name, true, rotation_deg, translation_m};
            eval.max_rotation_deg = std::max(eval.max_rotation_deg, rotation_deg);
            eval.max_translation_m = std::max(eval.max_translation_m, translation_m);
            ++eval.placed;
        }
        eval.scans.push_back(error);
    }
    for (const NamedPose& e : estimated) {
        if (!truth_index.contains(e.name)) eval.unknown.push_back(e.name);
    }
    add_best_fit(pairs, eval);
    return eval;
}

}  // namespace anascan
