#pragma once
/// \file
/// Local multi-view registration (paper §4.2.4, eq. 4): refines the poses of N scans at
/// once from the correspondences stored by each pair's final fine registration, so the
/// full scans are never needed (out-of-core). One scan stays fixed; every other scan i gets
/// a velocity field v_i(x) = c̄_i + c_i × x in the world frame, the linearised point-to-plane
/// residuals of all links are minimised as one 6(N-1) linear system, each scan moves by the
/// exact helical motion of its twist, and links whose residual stays large are dropped (the
/// paper's regression step). See docs/multiview-refinement.md.
///
/// Thread safety: `refine_multiview` is reentrant; it is single-threaded, so its results are
/// identical across runs and machines.

#include <cstddef>
#include <span>
#include <string_view>
#include <vector>

#include "anascan/processing/core/pose.hpp"
#include "anascan/processing/registration/fine/fine_registration.hpp"

namespace anascan {

/// One pairwise registration result kept for multi-view refinement: target scan j, source
/// scan k, and the final correspondences of `register_fine(source = k, target = j, ...)`
/// with `keep_correspondences = true` (x_i in scan k's frame; y_i, n_i in scan j's frame).
struct MultiviewLink {
    std::size_t target_index = 0;  ///< j, index into the pose list.
    std::size_t source_index = 0;  ///< k, index into the pose list; differs from j.
    std::vector<FineCorrespondence> correspondences;
};

/// Settings of one multi-view refinement. Callers use designated initialisers.
struct MultiviewRefinementConfig {
    std::size_t fixed_scan_index = 0;  ///< This scan's pose is kept exactly.
    int max_rounds = 15;               ///< Linearise-solve-move-prune rounds (paper: 10-20).
    /// A link whose weighted RMS point-to-plane residual (metres) exceeds this after a
    /// round is a candidate for dropping.
    double max_link_rms_m = 0.002;
    /// A link is also a candidate when its RMS exceeds this multiple of the median RMS of
    /// the active links ...
    double median_rms_factor = 2.5;
    /// ... and this floor (metres), so that exact data (median near 0) drops nothing.
    double median_rule_floor_m = 0.0005;
    /// Links with fewer usable correspondences (finite, weight > 0) are ignored from start.
    std::size_t min_link_correspondences = 10;
    /// Stop when no scan's step rotates by more than this (radians) ...
    double rotation_tolerance_rad = 1e-8;
    /// ... nor moves its reference point (centroid of its correspondences) by more than
    /// this (metres), and no link was dropped in the round.
    double translation_tolerance_m = 1e-8;
    /// Tikhonov weight added to the diagonal, relative to the mean diagonal of the scaled
    /// normal matrix: keeps weak directions still instead of letting them drift.
    double tikhonov_relative = 1e-10;
    /// Underconstrained when the smallest / largest LDLT pivot of the scaled system is below
    /// this (a scan that can slide, e.g. linked only by planar overlaps).
    double degeneracy_threshold = 1e-7;
    /// Up to this many free scans the system is solved densely (Eigen::LDLT), beyond it
    /// with Eigen::SimplicialLDLT.
    std::size_t max_dense_scans = 200;
};

enum class MultiviewStatus {
    kConverged,         ///< Every linked scan's last step was below both tolerances.
    kMaxRounds,         ///< Still moving after max_rounds (poses are usable).
    kDisconnected,      ///< Some scans have no chain of links to the fixed scan: see
                        ///< MultiviewRefinementResult::disconnected_scans (poses unchanged).
    kUnderconstrained,  ///< The linked scans can slide: the system is rank-deficient.
    kInvalidInput,      ///< Bad index, non-finite pose, or no scans; poses are the input.
};

/// Short English name ("converged", "disconnected", ...), for logs and JSON.
std::string_view to_string(MultiviewStatus status);

/// Per-link figures, in the order of the input links.
struct MultiviewLinkReport {
    std::size_t correspondence_count = 0;  ///< Usable correspondences (finite, weight > 0).
    /// Weighted RMS point-to-plane residual ε_mv (metres) at the input poses.
    double rms_before_m = 0.0;
    double rms_after_m = 0.0;   ///< The same at the final poses (also for dropped links).
    bool ignored = false;       ///< Too few usable correspondences: never used.
    bool dropped = false;       ///< Removed by the regression step.
    int dropped_in_round = -1;  ///< 1-based round that dropped it, -1 when kept.
};

/// Outcome of a multi-view refinement.
struct MultiviewRefinementResult {
    MultiviewStatus status = MultiviewStatus::kInvalidInput;
    /// True when the linked scans' last step was below the tolerances, whatever the status.
    bool converged = false;
    std::vector<Pose> T_world_scan;  ///< Final poses; disconnected scans keep their input.
    std::vector<std::size_t> disconnected_scans;  ///< Ascending scan indices.
    std::vector<MultiviewLinkReport> links;       ///< One per input link.
    int rounds = 0;                               ///< Rounds run (solve + move + prune).
    /// Smallest / largest LDLT pivot of the scaled system in the last round (0..1).
    double pivot_ratio = 0.0;
    double time_s = 0.0;  ///< Wall-clock time of the call, seconds.
};

/// Refines `T_world_scan_initial` (one pose per scan) from the stored pairwise
/// correspondences in `links` (paper eq. 4). Never throws on bad data; reports status.
MultiviewRefinementResult refine_multiview(std::span<const Pose> T_world_scan_initial,
                                           std::span<const MultiviewLink> links,
                                           const MultiviewRefinementConfig& config);

}  // namespace anascan
