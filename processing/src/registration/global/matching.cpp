// Candidate correspondences, pairwise consistency and rigid fits of global registration.
#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include <Eigen/SVD>
#include <algorithm>
#include <cmath>
#include <numbers>

#include "registration/global/steps.hpp"

namespace anascan::detail {
namespace {

bool similar(const FeaturePatch& s, const FeaturePatch& t, const FeatureMatchingConfig& config) {
    if (s.radius_index != t.radius_index || s.side != t.side || s.level != t.level) return false;
    const double tolerance = std::max(config.descriptor_tolerance,
                                      config.descriptor_fraction * std::abs(s.mean_volume - 0.5));
    if (std::abs(s.mean_volume - t.mean_volume) > tolerance) return false;
    const double larger = std::max(s.extent_m[0], t.extent_m[0]);
    const double smaller = std::min(s.extent_m[0], t.extent_m[0]);
    return larger <= config.max_extent_ratio * smaller;
}

double tolerance_m(const FeaturePatch& s, const FeaturePatch& t,
                   const FeatureMatchingConfig& config) {
    return config.distance_tolerance_m +
           config.distance_extent_fraction * std::max(s.extent_m[0], t.extent_m[0]);
}

double angle_between(const Eigen::Vector3d& a, const Eigen::Vector3d& b) {
    return std::acos(std::clamp(a.dot(b), -1.0, 1.0));
}

/// Barycentre distances (metres) and normal angles (radians) between all patches of one
/// scan, so that the N² candidate pairs need table look-ups only.
struct PatchGeometry {
    std::size_t count = 0;
    std::vector<float> distance_m;
    std::vector<float> angle_rad;

    explicit PatchGeometry(const FeaturePatchResult& scan)
        : count(scan.patches.size()), distance_m(count * count), angle_rad(count * count) {
        for (std::size_t i = 0; i < count; ++i) {
            for (std::size_t j = 0; j < count; ++j) {
                const FeaturePatch& a = scan.patches[i];
                const FeaturePatch& b = scan.patches[j];
                distance_m[i * count + j] =
                    static_cast<float>((a.barycentre_m - b.barycentre_m).norm());
                angle_rad[i * count + j] = static_cast<float>(angle_between(a.normal, b.normal));
            }
        }
    }
    float distance(std::size_t i, std::size_t j) const { return distance_m[i * count + j]; }
    float angle(std::size_t i, std::size_t j) const { return angle_rad[i * count + j]; }
};

/// Distances between the two barycentres and angles between the two normals agree in both
/// scans (within the candidates' tolerances); no patch is used twice.
bool pair_consistent(const PatchGeometry& source, const PatchGeometry& target,
                     const FeatureCorrespondence& a, const FeatureCorrespondence& b,
                     float max_angle_rad) {
    if (a.source_patch == b.source_patch || a.target_patch == b.target_patch) return false;
    const float ds = source.distance(a.source_patch, b.source_patch);
    const float dt = target.distance(a.target_patch, b.target_patch);
    if (std::abs(ds - dt) > static_cast<float>(a.tolerance_m + b.tolerance_m)) return false;
    const float angle_s = source.angle(a.source_patch, b.source_patch);
    const float angle_t = target.angle(a.target_patch, b.target_patch);
    return std::abs(angle_s - angle_t) <= max_angle_rad;
}

}  // namespace

std::vector<FeatureCorrespondence> candidate_correspondences(const FeaturePatchResult& source,
                                                             const FeaturePatchResult& target,
                                                             const FeatureMatchingConfig& config) {
    std::vector<std::pair<double, FeatureCorrespondence>> ranked;
    for (std::size_t i = 0; i < source.patches.size(); ++i) {
        for (std::size_t j = 0; j < target.patches.size(); ++j) {
            const FeaturePatch& s = source.patches[i];
            const FeaturePatch& t = target.patches[j];
            if (!similar(s, t, config)) continue;
            ranked.push_back(
                {std::abs(s.mean_volume - t.mean_volume), {i, j, tolerance_m(s, t, config)}});
        }
    }
    std::stable_sort(ranked.begin(), ranked.end(),
                     [](const auto& a, const auto& b) { return a.first < b.first; });
    if (ranked.size() > config.max_candidates) ranked.resize(config.max_candidates);
    std::vector<FeatureCorrespondence> candidates;
    candidates.reserve(ranked.size());
    for (const auto& entry : ranked) candidates.push_back(entry.second);
    return candidates;
}

ConsistencyGraph consistency_graph(const FeaturePatchResult& source,
                                   const FeaturePatchResult& target,
                                   std::span<const FeatureCorrespondence> candidates,
                                   const FeatureMatchingConfig& config) {
    ConsistencyGraph graph;
    graph.size = candidates.size();
    graph.consistent.assign(graph.size * graph.size, 0);
    graph.degree.assign(graph.size, 0);
    const auto max_angle_rad =
        static_cast<float>(config.max_normal_angle_deg * std::numbers::pi / 180.0);
    const PatchGeometry source_geometry(source), target_geometry(target);
    tbb::parallel_for(tbb::blocked_range<std::size_t>(0, graph.size, 32), [&](auto range) {
        for (std::size_t a = range.begin(); a < range.end(); ++a) {
            for (std::size_t b = 0; b < graph.size; ++b) {
                if (!pair_consistent(source_geometry, target_geometry, candidates[a], candidates[b],
                                     max_angle_rad)) {
                    continue;
                }
                graph.consistent[a * graph.size + b] = 1;
                ++graph.degree[a];
            }
        }
    });
    return graph;
}

std::optional<Pose> fit_rigid(const FeaturePatchResult& source, const FeaturePatchResult& target,
                              std::span<const FeatureCorrespondence> set) {
    std::vector<Eigen::Vector3d> s_points, t_points;
    std::vector<double> weights;
    for (const FeatureCorrespondence& c : set) {
        const FeaturePatch& s = source.patches[c.source_patch];
        const FeaturePatch& t = target.patches[c.target_patch];
        const double w = 1.0 / (c.tolerance_m * c.tolerance_m);
        const double lever_m = 2.0 * c.tolerance_m;  // Normal offsets: direction constraints.
        s_points.insert(s_points.end(), {s.barycentre_m, s.barycentre_m + lever_m * s.normal});
        t_points.insert(t_points.end(), {t.barycentre_m, t.barycentre_m + lever_m * t.normal});
        weights.insert(weights.end(), {w, 0.5 * w});
    }
    double w_sum = 0.0;
    Eigen::Vector3d s_mean = Eigen::Vector3d::Zero(), t_mean = Eigen::Vector3d::Zero();
    for (std::size_t i = 0; i < weights.size(); ++i) {
        w_sum += weights[i];
        s_mean += weights[i] * s_points[i];
        t_mean += weights[i] * t_points[i];
    }
    if (!(w_sum > 0.0)) return std::nullopt;
    s_mean /= w_sum;
    t_mean /= w_sum;
    Eigen::Matrix3d cross = Eigen::Matrix3d::Zero(), spread = Eigen::Matrix3d::Zero();
    for (std::size_t i = 0; i < weights.size(); ++i) {
        cross += weights[i] * (s_points[i] - s_mean) * (t_points[i] - t_mean).transpose();
        spread += weights[i] * (s_points[i] - s_mean) * (s_points[i] - s_mean).transpose();
    }
    const Eigen::Vector3d spread_values =
        Eigen::JacobiSVD<Eigen::Matrix3d>(spread).singularValues();
    if (!(spread_values[1] > 1e-4 * spread_values[0])) return std::nullopt;  // Collinear.
    const Eigen::JacobiSVD<Eigen::Matrix3d> svd(cross, Eigen::ComputeFullU | Eigen::ComputeFullV);
    Eigen::Matrix3d d = Eigen::Matrix3d::Identity();
    d(2, 2) = (svd.matrixV() * svd.matrixU().transpose()).determinant() < 0.0 ? -1.0 : 1.0;
    Pose T = Pose::Identity();
    T.linear() = svd.matrixV() * d * svd.matrixU().transpose();
    T.translation() = t_mean - T.linear() * s_mean;
    return T;
}

}  // namespace anascan::detail

namespace anascan {

FeatureMatchingResult match_features(const FeaturePatchResult& source,
                                     const FeaturePatchResult& target,
                                     const FeatureMatchingConfig& config) {
    FeatureMatchingResult result;
    const auto candidates = detail::candidate_correspondences(source, target, config);
    result.candidate_count = candidates.size();
    const detail::ConsistencyGraph graph =
        detail::consistency_graph(source, target, candidates, config);
    result.consistent_count = static_cast<std::size_t>(
        std::count_if(graph.degree.begin(), graph.degree.end(), [](auto d) { return d > 0; }));
    result.hypotheses = detail::forward_search(source, target, candidates, graph, config);
    return result;
}

}  // namespace anascan
