// The rating of a registered pair at its final pose (paper §4.2.2): RMS distance, overlap,
// normal deviation, degeneracy, and the final correspondences for multi-view (eq. 4).
#include <cmath>
#include <numbers>

#include "registration/fine/steps.hpp"

namespace anascan::fine_detail {
namespace {

bool overlaps(const Match& match, double overlap_distance_m) {
    return match.target_index != Match::kNone &&
           match.distance_sq_m2 <= overlap_distance_m * overlap_distance_m;
}

// Overlap fraction, the paper's ε_pw and the normal deviation, over overlapping samples.
void rate_overlap(const RatingInput& in, std::span<const Match> matches,
                  const FineRegistrationConfig& config, FineRegistrationResult& result) {
    const Eigen::Matrix3d R = in.T_local.linear();
    const bool with_normals = !in.samples.normals.empty();
    std::size_t overlapping = 0;
    double distance_sq_sum = 0.0;
    double angle_sum_rad = 0.0;
    for (std::size_t i = 0; i < matches.size(); ++i) {
        if (!overlaps(matches[i], config.overlap_distance_m)) continue;
        ++overlapping;
        distance_sq_sum += matches[i].distance_sq_m2;
        if (!with_normals) continue;
        const Eigen::Vector3d n_source = R * in.samples.normals[i].cast<double>();
        const Eigen::Vector3d n_target = in.target.normals[matches[i].target_index].cast<double>();
        angle_sum_rad += std::atan2(n_source.cross(n_target).norm(), n_source.dot(n_target));
    }
    result.overlap_fraction =
        matches.empty() ? 0.0 : static_cast<double>(overlapping) / matches.size();
    if (overlapping == 0) return;
    const double count = static_cast<double>(overlapping);
    result.rms_point_distance_m = std::sqrt(distance_sq_sum / count);
    if (with_normals)
        result.normal_deviation_deg = angle_sum_rad / count * 180.0 / std::numbers::pi;
}

std::vector<FineCorrespondence> collect_correspondences(const RatingInput& in,
                                                        std::span<const Match> matches) {
    std::vector<FineCorrespondence> out;
    for (std::size_t i = 0; i < matches.size(); ++i) {
        const Match& m = matches[i];
        if (m.target_index == Match::kNone || m.weight <= 0.0f) continue;
        FineCorrespondence c;
        c.source_point_m = in.source_origin_m + in.samples.points[i].cast<double>();
        c.target_point_m = in.target_origin_m + in.target.points[m.target_index].cast<double>();
        c.target_normal = in.target.normals[m.target_index];
        c.residual_m = m.residual_m;
        c.weight = m.weight;
        out.push_back(c);
    }
    return out;
}

}  // namespace

void rate_final_pose(const RatingInput& in, const FineRegistrationConfig& config,
                     FineRegistrationResult& result) {
    std::vector<Match> matches(in.samples.points.size());
    std::vector<Accumulation> chunk_sums;
    const Accumulation sums = match_and_accumulate(
        in.samples, in.target, in.T_local, match_settings(config, in.gate_m), matches, chunk_sums);
    result.inlier_count = sums.inliers;
    result.rms_m = sums.inliers == 0
                       ? 0.0
                       : std::sqrt(sums.residual_sq_sum / static_cast<double>(sums.inliers));
    result.degeneracy = measure_degeneracy(sums.H, in.samples.length_m);
    rate_overlap(in, matches, config, result);
    if (config.keep_correspondences) result.correspondences = collect_correspondences(in, matches);
}

}  // namespace anascan::fine_detail
