#pragma once
/// \file
/// Whether the scans of one group agree with each other in their current poses. Each scan
/// was placed by a link to its neighbours; a chain of links that each fit (large dressed
/// faces fit a plane anywhere) can still leave scans that contradict the others they now
/// overlap. For every pair of scans whose bounds overlap in space this checks:
///  - **crossing normals**: points of one scan near the other's surface must share its
///    normal direction (sign ignored); crossing planes disagree;
///  - **free space**: one scan's points must not lie in front of the other's surface as
///    seen from the other's sensor (`check_free_space`), both ways;
///  - **overlap at a large angle**: the median normal angle over the near points;
///  - **surfaces apart**: the median offset of the near points along the other's normal,
///    against the scans' noise (a look-alike of a near-symmetric stone fits its faces but
///    not its relief).
/// Every threshold is a multiple of the scans' own sample spacing, noise and normal noise,
/// measured here from the clouds (or given). Pure geometry: no devices, no I/O.
/// See docs/scan-registration.md "Group consistency".
///
/// Thread safety: all functions are reentrant.

#include <Eigen/Core>
#include <cstddef>
#include <optional>
#include <span>
#include <string>
#include <vector>

#include "anascan/processing/core/point_cloud.hpp"
#include "anascan/processing/core/pose.hpp"
#include "anascan/processing/evaluation/free_space.hpp"

namespace anascan {

/// One scan of the group: its cloud (scan frame; unit normals for the normal tests, sign
/// free) and its pose in the group's frame.
struct ConsistencyScan {
    const PointCloud* cloud = nullptr;
    Pose T_group_scan = Pose::Identity();
    /// Sensor position in the scan frame; without it the free-space test is skipped.
    std::optional<Eigen::Vector3d> sensor_origin_scan_m;
    double spacing_m = 0.0;  ///< Median sample spacing; 0: measured here.
    double noise_m = 0.0;    ///< Point-to-tangent-plane noise; 0: measured here (needs normals).
};

struct GroupConsistencyConfig {
    std::size_t max_samples = 3000;  ///< Points of each scan examined per pair (evenly).
    /// A point is near the other surface within this many of the pair's larger sample
    /// spacing plus `near_noise_factor` noises.
    double near_spacing_factor = 2.0;
    double near_noise_factor = 3.0;
    /// A near point crosses when its normal and the other surface's differ by more than
    /// this multiple of the scans' median neighbour-to-neighbour normal angle (their
    /// normal noise), and at least `min_crossing_angle_deg`: between true scans of a real
    /// scanner the normals differ far more than within one scan (bunny pairs at the bun.conf
    /// poses: medians of 10-14°), and 8° flagged true pairs of the simulated small block.
    double crossing_noise_factor = 4.0;
    double min_crossing_angle_deg = 20.0;
    /// A pair disagrees when more than this fraction of its near points cross (edges, where
    /// a near point's neighbour lies on the next face, gave up to 27 % on true pairs) ...
    double max_crossing_fraction = 0.4;
    /// ... counted from this many near points, and at least this fraction of the points
    /// examined: a pair that overlaps only along an edge says little about normals or relief.
    std::size_t min_near_samples = 200;
    double min_near_fraction = 0.1;
    /// A pair disagrees when the median offset of its near points along the other surface's
    /// normal exceeds this multiple of the pair's noise (at the true pose two independent
    /// noisy surfaces give 0.95 of it). 0: off, the default: the noise is measured within one
    /// scan, and between true scans of a real scanner the offset is larger (bunny pairs at
    /// the bun.conf poses: 1.9-6.5 times); simulated structured-light sessions use 1.5 (true
    /// pairs 0.7-1.2, the small block's 180° look-alike 3.8, docs/live-registration.md).
    double max_offset_noise_factor = 0.0;
    /// Free space at the measured defaults; its tolerance is at least
    /// `free_space_noise_factor` noises (a noisy device's surface is thick).
    FreeSpaceConfig free_space{};
    double free_space_noise_factor = 4.0;
};

/// Figures of one pair (indices into the scans given).
struct PairConsistency {
    std::size_t a = 0, b = 0;
    std::size_t near_samples = 0;          ///< Points of either near the other's surface.
    double crossing_fraction = 0.0;        ///< Of those, whose normals cross.
    double median_normal_angle_deg = 0.0;  ///< Over the near points (sign ignored).
    double crossing_angle_deg = 0.0;       ///< The threshold used for this pair.
    double median_offset_m = 0.0;          ///< Of the near points along the other's normal.
    double noise_m = 0.0;                  ///< The pair's noise: RMS of the two scans' noises.
    FreeSpaceResult b_seen_from_a{};       ///< b's points against a's view.
    FreeSpaceResult a_seen_from_b{};       ///< a's points against b's view.
    bool agrees = true;
    /// Why not ("free space", "angle", "normals cross", "surfaces apart"); empty if agrees.
    std::string reason;
};

/// Figures of one scan over its pairs.
struct ScanConsistency {
    std::size_t overlapping = 0;  ///< Pairs tested (bounds overlap, enough evidence).
    std::size_t disagreeing = 0;  ///< Of those, that disagree.
    bool taken_out = false;       ///< Chosen by `take_out_order` to restore agreement.
    /// Its disagreeing pair of most violations (index into `GroupConsistency::pairs`).
    std::optional<std::size_t> worst_pair;
};

struct GroupConsistency {
    std::vector<PairConsistency> pairs;  ///< Every pair whose bounds overlap.
    std::vector<ScanConsistency> scans;  ///< One per scan given.
    /// Scans to take out, worst first, so that the rest agree pairwise.
    std::vector<std::size_t> take_out;
    bool consistent = true;  ///< No pair disagrees.
};

/// Checks every overlapping pair of `scans` in their current poses.
GroupConsistency check_group_consistency(std::span<const ConsistencyScan> scans,
                                         const GroupConsistencyConfig& config);

/// Tests one pair (`a` and `b` in the group's frame); indices of the result are 0 and 1.
PairConsistency check_pair_consistency(const ConsistencyScan& a, const ConsistencyScan& b,
                                       const GroupConsistencyConfig& config);

/// The scans to take out of a group, worst first, until no remaining pair disagrees: each
/// step takes the scan with the most disagreeing pairs among those kept (ties: the larger
/// index, the later placement). Fills `GroupConsistency::take_out` and `ScanConsistency`.
void choose_take_out(GroupConsistency& group);

/// "scan 3 disagrees with scan 1: normals cross on 42 % of 900 near points (> 15 %)".
std::string describe(const PairConsistency& pair, std::span<const std::string> names);

}  // namespace anascan
