#include "anascan/processing/pose_evaluation.hpp"

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
    for (const NamedPose& t : truth) {
        ScanPoseError error{.name = t.name};
        if (auto it = estimated_index.find(t.name); it != estimated_index.end()) {
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
    return eval;
}

}  // namespace anascan
