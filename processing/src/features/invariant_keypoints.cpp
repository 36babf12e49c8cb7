#include "anascan/processing/features/invariant_keypoints.hpp"

#include <Eigen/Eigenvalues>
#include <algorithm>
#include <cmath>

#include "anascan/processing/spatial/kdtree.hpp"

namespace anascan {
namespace {

/// Deviation of V from 1/2 on `side` (negative on the other side).
double side_deviation(float volume, CurvatureSide side) {
    const double d = static_cast<double>(volume) - 0.5;
    return side == CurvatureSide::kConcave ? d : -d;
}

/// Per site its deviation on `side` at radius k where salient, else 0.
std::vector<double> salient_deviations(const IntegralInvariantResult& inv, std::size_t k,
                                       CurvatureSide side, const InvariantKeypointConfig& config) {
    std::vector<double> deviation(inv.site_positions.size(), 0.0), positive;
    for (std::size_t i = 0; i < deviation.size(); ++i) {
        if (!inv.is_valid(i, k)) continue;
        deviation[i] = std::max(0.0, side_deviation(inv.volume[i][k], side));
        if (deviation[i] > 0.0) positive.push_back(deviation[i]);
    }
    double threshold = config.min_deviation;
    if (!positive.empty()) {
        const auto at = static_cast<std::size_t>(config.salient_quantile *
                                                 static_cast<double>(positive.size() - 1));
        std::nth_element(positive.begin(), positive.begin() + static_cast<std::ptrdiff_t>(at),
                         positive.end());
        threshold = std::max(threshold, positive[at]);
    }
    for (double& d : deviation) d = d >= threshold ? d - threshold : 0.0;
    return deviation;
}

struct Search {
    const IntegralInvariantResult& inv;
    const KdTree& tree;
    const std::vector<double>& weight;  ///< Salient deviation above the threshold, else 0.
};

bool is_local_maximum(const Search& s, std::size_t i, float radius_m, std::vector<Neighbor>& near) {
    s.tree.radius_any_order(s.inv.site_positions[i], radius_m, near);
    for (const Neighbor& nb : near) {
        const double w = s.weight[nb.index];
        if (w > s.weight[i] || (w == s.weight[i] && nb.index < i)) return false;
    }
    return true;
}

/// The weighted support of site i: its keypoint, or nothing when too small or a ridge.
bool refine(const Search& s, std::size_t i, float radius_m, const InvariantKeypointConfig& config,
            std::vector<Neighbor>& near, Eigen::Vector3d& position) {
    s.tree.radius_any_order(s.inv.site_positions[i], radius_m, near);
    double total = 0.0;
    std::size_t count = 0;
    Eigen::Vector3d sum = Eigen::Vector3d::Zero();
    for (const Neighbor& nb : near) {
        const double w = s.weight[nb.index];
        total += w;
        count += w > 0.0;
        sum += w * s.inv.site_positions[nb.index].cast<double>();
    }
    if (count < config.min_support_sites || !(total > 0.0)) return false;
    const Eigen::Vector3d mean = sum / total;
    Eigen::Matrix3d covariance = Eigen::Matrix3d::Zero();
    for (const Neighbor& nb : near) {
        const Eigen::Vector3d d = s.inv.site_positions[nb.index].cast<double>() - mean;
        covariance += s.weight[nb.index] * d * d.transpose();
    }
    const Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> eigen(covariance / total);
    const Eigen::Vector3d l = eigen.eigenvalues().cwiseMax(0.0).cwiseSqrt();
    if (!(l[1] >= config.min_isotropy * l[2])) return false;  // Ascending: l[2] is the major.
    position = s.inv.origin_m + mean;
    return true;
}

void add_keypoints(const IntegralInvariantResult& inv, const KdTree& tree, std::size_t k,
                   CurvatureSide side, const InvariantKeypointConfig& config,
                   std::vector<InvariantKeypoint>& out) {
    const std::vector<double> weight = salient_deviations(inv, k, side, config);
    const Search search{inv, tree, weight};
    const auto suppression_m = static_cast<float>(config.suppression_radii * inv.radii_m[k]);
    const auto support_m = static_cast<float>(config.support_radii * inv.radii_m[k]);
    std::vector<Neighbor> near;
    for (std::size_t i = 0; i < weight.size(); ++i) {
        if (!(weight[i] > 0.0) || !is_local_maximum(search, i, suppression_m, near)) continue;
        Eigen::Vector3d position;
        if (!refine(search, i, support_m, config, near, position)) continue;
        const double deviation = std::abs(static_cast<double>(inv.volume[i][k]) - 0.5);
        out.push_back(
            {.radius_index = k, .side = side, .position_m = position, .deviation = deviation});
    }
}

}  // namespace

std::vector<InvariantKeypoint> invariant_keypoints(const IntegralInvariantResult& invariants,
                                                   const InvariantKeypointConfig& config) {
    std::vector<InvariantKeypoint> out;
    if (invariants.status != IntegralInvariantStatus::kOk) return out;
    const KdTree tree(invariants.site_positions);
    for (std::size_t k = 0; k < kInvariantRadii; ++k) {
        for (CurvatureSide side : {CurvatureSide::kConvex, CurvatureSide::kConcave}) {
            add_keypoints(invariants, tree, k, side, config, out);
        }
    }
    return out;
}

}  // namespace anascan
