#pragma once
/// \file
/// Private stages of multi-view refinement (multiview_refinement.cpp reads as these named
/// steps): link residuals, connectivity, assembly of the block normal equations of eq. 4,
/// their solve, and the helical move of every scan.
///
/// Unknowns: every free scan s (linked to the fixed scan, not the fixed scan itself) owns
/// one 6-block u_s = (c_s L, c̄'_s) of the velocity field v_s(x) = c̄'_s + c_s × (x - p_s) in
/// the world frame, written about its reference point p_s and with the rotation scaled by
/// the characteristic length L so that all unknowns are in metres (better conditioned).

#include <Eigen/Core>
#include <cstddef>
#include <map>
#include <span>
#include <utility>
#include <vector>

#include "anascan/processing/core/pose.hpp"
#include "anascan/processing/registration/multiview/multiview_refinement.hpp"

namespace anascan::multiview_detail {

using Matrix6d = Eigen::Matrix<double, 6, 6>;
using Vector6d = Eigen::Matrix<double, 6, 1>;

/// A correspondence counts when it is finite and has a positive weight.
bool usable(const FineCorrespondence& c);

/// Number of usable correspondences of a link.
std::size_t usable_count(const MultiviewLink& link);

/// Weighted RMS of the point-to-plane residual d_i = (T_world_k x_i - T_world_j y_i)·(R_j n_i)
/// of one link at the given poses (metres); 0 without usable correspondences.
double link_rms_m(const MultiviewLink& link, std::span<const Pose> T_world_scan);

/// True for every scan reachable from `fixed` over the active links.
std::vector<bool> connected_scans(std::size_t scan_count, std::size_t fixed,
                                  std::span<const MultiviewLink> links,
                                  const std::vector<bool>& active);

/// Where each scan's velocity field is written about, and the rotation scale.
struct Parametrisation {
    std::vector<Eigen::Vector3d> reference_m;  ///< p_s, world frame, per scan.
    double length_m = 1.0;                     ///< L (> 0).
    std::vector<int> block;                    ///< Unknown block of each scan, -1 if none.
    std::size_t block_count = 0;
};

/// Reference points (centroid of each scan's correspondence points in the world at the
/// given poses; the scan origin when it has none) and L (RMS distance of those points from
/// their scan's reference point).
Parametrisation make_parametrisation(std::span<const Pose> T_world_scan,
                                     std::span<const MultiviewLink> links,
                                     const std::vector<bool>& active);

/// Numbers the free scans (connected, not fixed) in ascending order.
void assign_blocks(Parametrisation& param, const std::vector<bool>& connected, std::size_t fixed);

/// The normal equations H u = -g of eq. 4, by 6×6 blocks.
struct BlockSystem {
    std::vector<Matrix6d> diagonal;                        ///< H_ss.
    std::map<std::pair<int, int>, Matrix6d> off_diagonal;  ///< H_ab for a < b.
    std::vector<Vector6d> gradient;                        ///< g_s.
};

/// Accumulates Σ w_i (d_i + J_k u_k + J_j u_j)² over the active links at the current poses.
BlockSystem assemble(std::span<const MultiviewLink> links, const std::vector<bool>& active,
                     std::span<const Pose> T_world_scan, const Parametrisation& param);

/// The solved steps u_s and the conditioning figure.
struct Steps {
    std::vector<Vector6d> u;   ///< One per block.
    double pivot_ratio = 0.0;  ///< Smallest / largest |LDLT pivot|, 0..1.
};

/// Solves (H + λ I) u = -g densely or sparsely (see MultiviewRefinementConfig).
Steps solve(const BlockSystem& system, const MultiviewRefinementConfig& config);

/// Moves every free scan by the exact helical motion of its step. Returns the largest step
/// as (rotation radians, reference-point translation metres).
std::pair<double, double> apply_steps(const Steps& steps, const Parametrisation& param,
                                      std::vector<Pose>& T_world_scan);

}  // namespace anascan::multiview_detail
