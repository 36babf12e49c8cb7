#pragma once
/// \file
/// Keypoints of a scan from its geometry: the local extrema of the integral-invariant
/// volume descriptor V_r (paper §4.2.1), one set per radius and curvature side. A site is a
/// keypoint when its deviation |V_r − 1/2| on its side is salient (above a quantile of the
/// scan's own deviations) and the largest of all salient sites within the suppression
/// radius; its position is the deviation-weighted mean of the salient sites around it, so
/// that it follows the surface's shape, not where the sites fell. Extrema elongated along a
/// ridge (an edge of a dressed block, where V_r is constant along the edge and the noise
/// decides where the maximum lies) are dropped. With sites placed densely (about one per
/// sample spacing), a rigidly moved copy of a scan and an overlapping scan of the same
/// surface find the same keypoints, unlike feature patches cut from sites on a grid of
/// the scan's frame.
///
/// Library code: no I/O, no threads of its own; reentrant.

#include <Eigen/Core>
#include <cstddef>
#include <vector>

#include "anascan/processing/features/feature_patches.hpp"
#include "anascan/processing/features/integral_invariants.hpp"

namespace anascan {

struct InvariantKeypointConfig {
    /// Salient: the deviation on its side is at least this quantile of the scan's valid
    /// deviations on that side (per radius), and at least `min_deviation`.
    double salient_quantile = 0.75;
    double min_deviation = 0.004;  ///< Noise floor of V_r (as FeaturePatchConfig).
    /// A keypoint is the largest salient deviation within this many radii r.
    double suppression_radii = 1.0;
    /// Its position and shape come from the salient sites within this many radii r.
    double support_radii = 1.0;
    /// A keypoint needs this many salient sites in its support.
    std::size_t min_support_sites = 4;
    /// ... spread in at least two directions: the minor principal extent of the support
    /// (in the tangent plane) at least this fraction of the major (a ridge gives ~0).
    double min_isotropy = 0.35;
};

struct InvariantKeypoint {
    std::size_t radius_index = 0;
    CurvatureSide side = CurvatureSide::kConvex;
    Eigen::Vector3d position_m = Eigen::Vector3d::Zero();  ///< Cloud frame (origin added).
    double deviation = 0.0;                                ///< |V_r − 1/2| at the extremum.
};

/// The keypoints of all radii and sides, ordered by (radius, side, site). Invalid
/// descriptors give none.
std::vector<InvariantKeypoint> invariant_keypoints(const IntegralInvariantResult& invariants,
                                                   const InvariantKeypointConfig& config = {});

}  // namespace anascan
