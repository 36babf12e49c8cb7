#pragma once
/// \file
/// How well two scans agree where they overlap, once both are in one frame: the
/// distances from sampled points of one scan to their nearest neighbours in the other.
/// When the other scan has normals, the distance is measured along the neighbour's normal
/// (point-to-plane), which removes the sampling spacing from the figure; otherwise it is
/// the point-to-point distance.

#include <cstddef>
#include <cstdint>

#include "anascan/processing/core/point_cloud.hpp"
#include "anascan/processing/spatial/kdtree.hpp"

namespace anascan {

struct AgreementConfig {
    /// A sample of A overlaps B when B has a point within this distance (metres). Choose
    /// several times the sample spacing so that misalignment shows in the distances
    /// instead of only shrinking the overlap.
    double overlap_radius_m = 0.005;
    std::size_t max_samples = 5000;  ///< Points of A sampled (evenly by index).
};

/// Figures of one directed pair (A against B).
struct PairAgreement {
    std::size_t samples = 0;         ///< Points of A examined.
    std::size_t overlapping = 0;     ///< Of those, how many overlap B.
    double overlap_fraction = 0.0;   ///< overlapping / samples.
    double median_distance_m = 0.0;  ///< Median nearest-neighbour distance (overlap).
    double rms_distance_m = 0.0;     ///< RMS nearest-neighbour distance (overlap).
    bool point_to_plane = false;     ///< Distances along B's normals (B had normals).
};

/// Measures A against B; both clouds must be in the same frame (their origins may
/// differ). `tree_b` indexes `b.positions`. Zero figures when nothing overlaps.
PairAgreement measure_agreement(const PointCloud& a, const PointCloud& b, const KdTree& tree_b,
                                const AgreementConfig& config);

}  // namespace anascan
