#include "anascan/processing/evaluation/scan_agreement.hpp"

#include <algorithm>
#include <cmath>
#include <vector>

namespace anascan {
namespace {

// Distance of `query` to the plane through B's point `index`; point-to-point where that
// point has no usable (zero) normal.
double distance_along_normal(const Eigen::Vector3f& query, const PointCloud& b,
                             std::uint32_t index) {
    const Eigen::Vector3f offset = query - b.positions[index];
    const Eigen::Vector3f& normal = b.normals[index];
    if (normal.squaredNorm() < 0.5f) return offset.norm();
    return std::abs(normal.dot(offset));
}

}  // namespace

PairAgreement measure_agreement(const PointCloud& a, const PointCloud& b, const KdTree& tree_b,
                                const AgreementConfig& config) {
    PairAgreement result;
    if (a.empty() || b.empty() || config.max_samples == 0) return result;
    const std::size_t stride = std::max<std::size_t>(1, a.size() / config.max_samples);
    const Eigen::Vector3f a_to_b = (a.origin_m - b.origin_m).cast<float>();
    const float radius_sq = static_cast<float>(config.overlap_radius_m * config.overlap_radius_m);

    result.point_to_plane = b.has_normals();

    std::vector<double> distances;
    Neighbor nearest;
    for (std::size_t i = 0; i < a.size(); i += stride) {
        ++result.samples;
        const Eigen::Vector3f query = a.positions[i] + a_to_b;
        if (!tree_b.nearest(query, nearest) || nearest.distance_sq_m2 > radius_sq) continue;
        distances.push_back(result.point_to_plane ? distance_along_normal(query, b, nearest.index)
                                                  : std::sqrt(nearest.distance_sq_m2));
    }
    result.overlapping = distances.size();
    result.overlap_fraction = static_cast<double>(result.overlapping) / result.samples;
    if (distances.empty()) return result;

    double sum_sq = 0.0;
    for (double d : distances) sum_sq += d * d;
    result.rms_distance_m = std::sqrt(sum_sq / distances.size());
    auto middle = distances.begin() + distances.size() / 2;
    std::nth_element(distances.begin(), middle, distances.end());
    result.median_distance_m = *middle;
    return result;
}

}  // namespace anascan
