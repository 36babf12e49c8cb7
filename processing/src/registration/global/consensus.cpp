// Forward search (Atkinson et al. 2004) over the consistent candidate correspondences.
#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <cmath>
#include <numbers>
#include <numeric>

#include "registration/global/steps.hpp"

namespace anascan::detail {
namespace {

/// The candidates' barycentres, normals and tolerances as flat float arrays: the inlier
/// counts of the search test every candidate against thousands of poses. Barycentres are
/// stored relative to a reference point per scan (cloud-frame coordinates may be site
/// coordinates, too large for float).
struct CandidateGeometry {
    Eigen::Vector3d source_reference_m = Eigen::Vector3d::Zero();
    Eigen::Vector3d target_reference_m = Eigen::Vector3d::Zero();
    std::vector<Eigen::Vector3f> source_barycentre, source_normal;
    std::vector<Eigen::Vector3f> target_barycentre, target_normal;
    std::vector<float> tolerance_sq_m2;

    CandidateGeometry(const FeaturePatchResult& source, const FeaturePatchResult& target,
                      std::span<const FeatureCorrespondence> candidates) {
        if (!candidates.empty()) {
            source_reference_m = source.patches[candidates[0].source_patch].barycentre_m;
            target_reference_m = target.patches[candidates[0].target_patch].barycentre_m;
        }
        for (const FeatureCorrespondence& c : candidates) {
            const FeaturePatch& s = source.patches[c.source_patch];
            const FeaturePatch& t = target.patches[c.target_patch];
            source_barycentre.push_back((s.barycentre_m - source_reference_m).cast<float>());
            source_normal.push_back(s.normal.cast<float>());
            target_barycentre.push_back((t.barycentre_m - target_reference_m).cast<float>());
            target_normal.push_back(t.normal.cast<float>());
            tolerance_sq_m2.push_back(static_cast<float>(c.tolerance_m * c.tolerance_m));
        }
    }
};

struct SearchContext {
    const FeaturePatchResult& source;
    const FeaturePatchResult& target;
    std::span<const FeatureCorrespondence> candidates;
    const ConsistencyGraph& graph;
    const FeatureMatchingConfig& config;
    double cos_max_angle = 0.0;
    CandidateGeometry geometry;
};

/// Candidates ordered by degree in the consistency graph (ties: index), descending.
std::vector<std::size_t> by_degree(const ConsistencyGraph& graph) {
    std::vector<std::size_t> order(graph.size);
    std::iota(order.begin(), order.end(), 0);
    std::stable_sort(order.begin(), order.end(), [&](std::size_t a, std::size_t b) {
        return graph.degree[a] > graph.degree[b];
    });
    return order;
}

/// A pose in the form the flat arrays need: R s' + t with t = R s0 + t_T − t0.
struct FloatPose {
    Eigen::Matrix3f R;
    Eigen::Vector3f t;
    FloatPose(const CandidateGeometry& g, const Pose& T)
        : R(T.linear().cast<float>()),
          t((T * g.source_reference_m - g.target_reference_m).cast<float>()) {}
};

/// Squared barycentre residual over squared tolerance (≤ 1 for an inlier), or −1 when the
/// normals disagree by more than the angle tolerance.
float normalized_residual_sq(const SearchContext& ctx, const FloatPose& T, std::size_t k) {
    const CandidateGeometry& g = ctx.geometry;
    if ((T.R * g.source_normal[k]).dot(g.target_normal[k]) <
        static_cast<float>(ctx.cos_max_angle)) {
        return -1.0f;
    }
    const Eigen::Vector3f d = T.R * g.source_barycentre[k] + T.t - g.target_barycentre[k];
    return d.squaredNorm() / g.tolerance_sq_m2[k];
}

/// Inliers of a pose: candidates within their distance and angle tolerances.
std::size_t inlier_count(const SearchContext& ctx, const Pose& T) {
    const FloatPose T_float(ctx.geometry, T);
    std::size_t count = 0;
    for (std::size_t k = 0; k < ctx.candidates.size(); ++k) {
        const float r_sq = normalized_residual_sq(ctx, T_float, k);
        count += r_sq >= 0.0f && r_sq <= 1.0f;
    }
    return count;
}

/// The consistent partner of `seed` whose pair pose has the most inliers.
std::optional<std::size_t> best_partner(const SearchContext& ctx, std::size_t seed,
                                        const std::vector<std::size_t>& order) {
    std::optional<std::size_t> best;
    std::size_t best_count = 0, tried = 0;
    for (std::size_t j : order) {
        if (tried >= ctx.config.seed_partners) break;
        if (!ctx.graph.at(seed, j)) continue;
        ++tried;
        const FeatureCorrespondence pair[] = {ctx.candidates[seed], ctx.candidates[j]};
        const std::optional<Pose> T = fit_rigid(ctx.source, ctx.target, pair);
        if (!T) continue;
        const std::size_t count = inlier_count(ctx, *T);
        if (count > best_count) {
            best_count = count;
            best = j;
        }
    }
    return best;
}

bool conflicts(const SearchContext& ctx, const std::vector<std::size_t>& set, std::size_t k) {
    for (std::size_t m : set) {
        if (m == k || !ctx.graph.at(m, k)) return true;
    }
    return false;
}

/// Grows the set one correspondence at a time: the smallest normalised residual under the
/// current fit that is within tolerance and consistent with every member; refits each step.
std::vector<std::size_t> grow(const SearchContext& ctx, std::vector<std::size_t> set) {
    while (true) {
        std::vector<FeatureCorrespondence> members;
        for (std::size_t m : set) members.push_back(ctx.candidates[m]);
        const std::optional<Pose> T = fit_rigid(ctx.source, ctx.target, members);
        if (!T) return set;
        const FloatPose T_float(ctx.geometry, *T);
        std::optional<std::size_t> next;
        float next_residual_sq = 1.0f;
        for (std::size_t k = 0; k < ctx.candidates.size(); ++k) {
            const float r_sq = normalized_residual_sq(ctx, T_float, k);
            if (r_sq < 0.0f || r_sq > next_residual_sq || conflicts(ctx, set, k)) continue;
            next_residual_sq = r_sq;
            next = k;
        }
        if (!next) return set;
        set.push_back(*next);
    }
}

/// Distinct locations among the inliers (source barycentres farther apart than twice the
/// base tolerance), so nested patches of one feature count once.
double spatial_score(const SearchContext& ctx, const std::vector<FeatureCorrespondence>& set) {
    std::vector<Eigen::Vector3d> counted;
    const double min_distance_m = 2.0 * ctx.config.distance_tolerance_m;
    for (const FeatureCorrespondence& c : set) {
        const Eigen::Vector3d& b = ctx.source.patches[c.source_patch].barycentre_m;
        const bool near = std::any_of(counted.begin(), counted.end(), [&](const auto& q) {
            return (q - b).norm() < min_distance_m;
        });
        if (!near) counted.push_back(b);
    }
    return static_cast<double>(counted.size());
}

std::optional<PoseHypothesis> make_hypothesis(const SearchContext& ctx,
                                              const std::vector<std::size_t>& set) {
    PoseHypothesis hypothesis;
    for (std::size_t m : set) hypothesis.inliers.push_back(ctx.candidates[m]);
    if (hypothesis.inliers.size() < ctx.config.min_inliers) return std::nullopt;
    const std::optional<Pose> T = fit_rigid(ctx.source, ctx.target, hypothesis.inliers);
    if (!T) return std::nullopt;
    hypothesis.T_target_source = *T;
    double sum_sq = 0.0;
    for (const FeatureCorrespondence& c : hypothesis.inliers) {
        const FeaturePatch& s = ctx.source.patches[c.source_patch];
        sum_sq +=
            (*T * s.barycentre_m - ctx.target.patches[c.target_patch].barycentre_m).squaredNorm();
    }
    hypothesis.rms_m = std::sqrt(sum_sq / static_cast<double>(hypothesis.inliers.size()));
    hypothesis.score = spatial_score(ctx, hypothesis.inliers);
    return hypothesis;
}

bool same_pose(const Pose& a, const Pose& b, const FeatureMatchingConfig& config) {
    const PoseDifference d = pose_difference(a, b);
    return d.rotation_deg < config.distinct_rotation_deg &&
           d.translation_m < config.distinct_translation_m;
}

/// Best score first (ties: more inliers, then smaller RMS); one per distinct pose.
std::vector<PoseHypothesis> distinct_best(std::vector<PoseHypothesis> all,
                                          const FeatureMatchingConfig& config) {
    std::stable_sort(all.begin(), all.end(), [](const auto& a, const auto& b) {
        if (a.score != b.score) return a.score > b.score;
        if (a.inliers.size() != b.inliers.size()) return a.inliers.size() > b.inliers.size();
        return a.rms_m < b.rms_m;
    });
    std::vector<PoseHypothesis> kept;
    for (PoseHypothesis& h : all) {
        if (kept.size() >= config.max_hypotheses) break;
        const bool seen = std::any_of(kept.begin(), kept.end(), [&](const auto& k) {
            return same_pose(k.T_target_source, h.T_target_source, config);
        });
        if (!seen) kept.push_back(std::move(h));
    }
    return kept;
}

}  // namespace

std::vector<PoseHypothesis> forward_search(const FeaturePatchResult& source,
                                           const FeaturePatchResult& target,
                                           std::span<const FeatureCorrespondence> candidates,
                                           const ConsistencyGraph& graph,
                                           const FeatureMatchingConfig& config) {
    const SearchContext ctx{source,
                            target,
                            candidates,
                            graph,
                            config,
                            std::cos(config.max_normal_angle_deg * std::numbers::pi / 180.0),
                            CandidateGeometry(source, target, candidates)};
    const std::vector<std::size_t> order = by_degree(graph);
    std::size_t seeds = std::min(config.seed_count, order.size());
    while (seeds > 0 && graph.degree[order[seeds - 1]] == 0) --seeds;
    // One slot per seed, collected in seed order: the result is thread-count free.
    std::vector<std::optional<PoseHypothesis>> found(seeds);
    tbb::parallel_for(tbb::blocked_range<std::size_t>(0, seeds, 1), [&](auto range) {
        for (std::size_t s = range.begin(); s < range.end(); ++s) {
            const std::optional<std::size_t> partner = best_partner(ctx, order[s], order);
            if (partner) found[s] = make_hypothesis(ctx, grow(ctx, {order[s], *partner}));
        }
    });
    std::vector<PoseHypothesis> all;
    for (std::optional<PoseHypothesis>& h : found) {
        if (h) all.push_back(std::move(*h));
    }
    return distinct_best(std::move(all), config);
}

}  // namespace anascan::detail
