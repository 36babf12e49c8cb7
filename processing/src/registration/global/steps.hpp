#pragma once
/// \file
/// Internal steps of global registration (not installed): candidate correspondences, the
/// pairwise consistency graph, weighted Kabsch fits and the forward search.

#include <cstdint>
#include <optional>
#include <span>
#include <vector>

#include "anascan/processing/registration/global/global_registration.hpp"
#include "anascan/processing/spatial/kdtree.hpp"

namespace anascan::detail {

/// Candidates: same radius, side and level; similar descriptor and extent. At most
/// config.max_candidates, the most similar descriptors first, then in patch order.
std::vector<FeatureCorrespondence> candidate_correspondences(const FeaturePatchResult& source,
                                                             const FeaturePatchResult& target,
                                                             const FeatureMatchingConfig& config);

/// Row-major N×N matrix: 1 where two candidates are geometrically consistent.
struct ConsistencyGraph {
    std::size_t size = 0;
    std::vector<std::uint8_t> consistent;
    std::vector<std::size_t> degree;  ///< Consistent partners per candidate.
    bool at(std::size_t a, std::size_t b) const { return consistent[a * size + b] != 0; }
};

ConsistencyGraph consistency_graph(const FeaturePatchResult& source,
                                   const FeaturePatchResult& target,
                                   std::span<const FeatureCorrespondence> candidates,
                                   const FeatureMatchingConfig& config);

/// Weighted Kabsch over barycentres and normal-offset points of the given candidates;
/// empty when the points do not fix a rotation (all on one line).
std::optional<Pose> fit_rigid(const FeaturePatchResult& source, const FeaturePatchResult& target,
                              std::span<const FeatureCorrespondence> set);

/// Forward searches from the best-connected seeds; distinct hypotheses, best first.
std::vector<PoseHypothesis> forward_search(const FeaturePatchResult& source,
                                           const FeaturePatchResult& target,
                                           std::span<const FeatureCorrespondence> candidates,
                                           const ConsistencyGraph& graph,
                                           const FeatureMatchingConfig& config);

/// Fraction of source sites that land within `distance_m` of a target site with a normal
/// within 30° under `T_target_source` (`target_sites` indexes target.site_positions).
double site_overlap_fraction(const IntegralInvariantResult& source,
                             const IntegralInvariantResult& target, const KdTree& target_sites,
                             const Pose& T_target_source, double distance_m);

/// A scan with its precomputed features.
struct DescribedScan {
    const PointCloud& cloud;
    const ScanFeatures& features;
    std::optional<Eigen::Vector3d> viewpoint_m;  ///< Sensor position (cloud frame), if known.
};

/// The second half of `register_global`: ranks the matching's hypotheses, refines and
/// verifies them, decides. Timing of matching and the features is left to the caller.
GlobalRegistrationResult refine_and_verify(const DescribedScan& source, const DescribedScan& target,
                                           FeatureMatchingResult matching,
                                           const GlobalRegistrationConfig& config);

}  // namespace anascan::detail
