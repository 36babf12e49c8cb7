#pragma once
/// \file
/// Feature patches (paper §4.2.1): for each descriptor radius, the sites of a scan are
/// clustered by their value of V_r into connected salient regions, and each region becomes
/// a feature with a barycentre, a mean normal and an extent.
///
/// Saliency is relative to the plane value 1/2: a site is salient at level l on the convex
/// side when 1/2 − V_r exceeds the l-th threshold of that side (likewise V_r − 1/2 on the
/// concave side). Thresholds are quantiles of the deviations over the valid sites, pooled
/// over the scans to be matched so that both scans cut their regions at the same values.
/// Patches are the connected components (over sites within ~1.5 site spacings) of each
/// (radius, side, level) set with enough sites; the levels nest, so a peak yields a small
/// patch inside a larger one. Deterministic: components are grown in site order.
///
/// Library code: no I/O, no threads; reentrant.

#include <Eigen/Core>
#include <array>
#include <cstddef>
#include <cstdint>
#include <span>
#include <vector>

#include "anascan/processing/features/integral_invariants.hpp"

namespace anascan {

/// Number of nested saliency levels per side.
inline constexpr std::size_t kSaliencyLevels = 3;

/// Which side of the plane value a patch lies on.
enum class CurvatureSide : std::uint8_t {
    kConvex = 0,   ///< V_r < 1/2 (a bump seen from outside).
    kConcave = 1,  ///< V_r > 1/2 (a hollow).
};

struct FeaturePatchConfig {
    /// Quantiles of |V_r − 1/2| (per radius and side, over valid sites) that set the
    /// levels; higher levels are smaller, more salient regions.
    std::array<double, kSaliencyLevels> level_quantiles{0.5, 0.75, 0.9};
    /// No level below this deviation |V_r − 1/2| (noise floor of the descriptor).
    double min_deviation = 0.004;
    /// Sites closer than this many site spacings are neighbours when growing regions.
    double neighbor_spacing_factor = 1.5;
    std::size_t min_sites = 6;  ///< Smaller regions are dropped.
};

/// |V_r − 1/2| thresholds, [radius][side][level], ascending in level.
struct SaliencyLevels {
    std::array<std::array<std::array<double, kSaliencyLevels>, 2>, kInvariantRadii> deviation{};
};

/// One feature: a connected region of salient sites at one radius.
struct FeaturePatch {
    std::size_t radius_index = 0;
    CurvatureSide side = CurvatureSide::kConvex;
    std::size_t level = 0;
    double mean_volume = 0.5;                                ///< Mean V_r of its sites.
    Eigen::Vector3d barycentre_m = Eigen::Vector3d::Zero();  ///< Cloud frame (origin in).
    Eigen::Vector3d normal = Eigen::Vector3d::UnitZ();       ///< Unit mean normal.
    Eigen::Vector3d extent_m = Eigen::Vector3d::Zero();      ///< Principal std devs, descending.
    std::size_t site_count = 0;
};

enum class FeaturePatchStatus {
    kOk,            ///< Patches extracted (possibly none: a featureless scan).
    kInvalidInput,  ///< The descriptors were invalid or the config out of range.
};

struct FeaturePatchResult {
    FeaturePatchStatus status = FeaturePatchStatus::kInvalidInput;
    std::vector<FeaturePatch> patches;
    std::array<std::size_t, kInvariantRadii> patch_count{};  ///< Per radius.
};

/// Thresholds from the pooled valid descriptors of `scans` (typically source and target).
SaliencyLevels saliency_levels(std::span<const IntegralInvariantResult* const> scans,
                               const FeaturePatchConfig& config);

/// Patches of one scan with the given thresholds.
FeaturePatchResult extract_feature_patches(const IntegralInvariantResult& invariants,
                                           const SaliencyLevels& levels,
                                           const FeaturePatchConfig& config);

/// Patches of one scan with thresholds from that scan alone.
FeaturePatchResult extract_feature_patches(const IntegralInvariantResult& invariants,
                                           const FeaturePatchConfig& config);

}  // namespace anascan
