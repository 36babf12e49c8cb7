#pragma once
/// \file
/// The integral-invariant volume descriptor V_r(p) of paper §4.2.1, eq. 1: the fraction of
/// the ball B_r(p) that lies inside the solid D whose boundary the scan samples, at four
/// radii. Discretised for partial scans (no closed surface needed): with n_p the unit
/// normal at p (pointing out of D) and h̄ the mean signed height n_p·(q − p) of the surface
/// samples q within r of p (taken from the cloud down-sampled to ~r/8, so that the samples
/// are roughly uniform per area),
///
///     V_r(p) ≈ 1/2 + 3 h̄ / (4 r),
///
/// i.e. half the ball plus the volume between the tangent plane and the surface over the
/// disk of radius r, divided by the ball volume. A sphere of radius R (p on it, D the
/// ball) gives exactly 1/2 − 3r/(16R) = the ball–ball intersection fraction; in general
/// V_r ≈ 1/2 − 3 H r / 16 with H the mean curvature (Pottmann et al. 2005). Flat → 1/2,
/// convex → below 1/2, concave → above 1/2. See docs/global-registration.md.
///
/// Library code: no I/O; TBB loops write one slot per site, so results do not depend on
/// the number of threads. `compute_integral_invariants` is reentrant.

#include <Eigen/Core>
#include <array>
#include <cstddef>
#include <cstdint>
#include <vector>

#include "anascan/processing/core/point_cloud.hpp"

namespace anascan {

/// Number of descriptor radii (the paper uses four).
inline constexpr std::size_t kInvariantRadii = 4;

/// Radii in metres, smallest first.
using InvariantRadii = std::array<double, kInvariantRadii>;

struct IntegralInvariantConfig {
    InvariantRadii radii_m{0.008, 0.012, 0.018, 0.027};  ///< Ball radii r, metres, > 0.
    /// Descriptors are computed at sites one per voxel of this edge (metres) rather than at
    /// every point; 0 = a quarter of the smallest radius.
    double site_spacing_m = 0.0;
    /// The cloud is down-sampled to this fraction of r before summing heights (~r/8 gives
    /// 100–200 samples per ball).
    double sample_spacing_fraction = 0.125;
    /// Fewer samples within r than this: the site is invalid at that radius.
    std::size_t min_neighbors = 30;
    /// The samples' centroid, projected to the tangent plane, farther from p than this
    /// fraction of r: the ball crosses the scan boundary, the site is invalid there.
    double max_centroid_offset_fraction = 0.3;
    std::size_t chunk_size = 256;  ///< Sites per TBB work unit.
    /// Sites and samples by a minimum distance in point order (`min_distance_sample`)
    /// instead of voxel grids aligned with the frame: a rigidly moved copy of a cloud then
    /// gives the same sites and descriptors. Sites are then the points themselves.
    bool frame_free_sampling = false;
};

enum class IntegralInvariantStatus {
    kOk,            ///< Descriptors computed (some sites may still be invalid).
    kInvalidInput,  ///< No points, no normals, inconsistent attributes or a bad config.
};

/// Descriptors at the sites of one cloud. Positions and normals are in the cloud's local
/// frame (add `origin_m` for the cloud frame).
struct IntegralInvariantResult {
    IntegralInvariantStatus status = IntegralInvariantStatus::kInvalidInput;
    InvariantRadii radii_m{};                            ///< The radii used, metres.
    double site_spacing_m = 0.0;                         ///< The site spacing used, metres.
    Eigen::Vector3d origin_m = Eigen::Vector3d::Zero();  ///< The cloud's origin_m.
    std::vector<Eigen::Vector3f> site_positions;         ///< Metres, local frame.
    std::vector<Eigen::Vector3f> site_normals;           ///< Unit, out of the solid (zero: none).
    /// V_r per site and radius, 0..1; meaningful only where `is_valid`.
    std::vector<std::array<float, kInvariantRadii>> volume;
    /// Bit k set: the descriptor at radius k is valid (interior, enough samples).
    std::vector<std::uint8_t> valid_bits;
    std::array<std::size_t, kInvariantRadii> valid_count{};     ///< Valid sites per radius.
    std::array<std::size_t, kInvariantRadii> boundary_count{};  ///< Invalid: scan boundary.
    std::array<std::size_t, kInvariantRadii> sparse_count{};    ///< Invalid: too few samples.
    double time_s = 0.0;                                        ///< Wall-clock seconds.

    bool is_valid(std::size_t site, std::size_t radius_index) const {
        return (valid_bits[site] >> radius_index) & 1u;
    }
};

/// Median distance (metres) from a point to its nearest neighbour, over up to
/// `max_samples` points spread evenly by index; 0 for fewer than two points.
double median_sample_spacing_m(const PointCloud& cloud, std::size_t max_samples = 2000);

/// Four radii in geometric progression (ratio 1.5) starting at `smallest_m`.
InvariantRadii geometric_radii_m(double smallest_m);

/// Radii for an object of diagonal `object_size_m` (metres): the smallest is 4% of it, so
/// the largest (13.5%) still fits inside a partial scan's interior.
InvariantRadii radii_for_object_size_m(double object_size_m);

/// Radii from the median sample spacing (metres): the smallest is 12 spacings, so that a
/// ball down-sampled to r/8 holds samples well above the scanner's spacing.
InvariantRadii radii_for_sample_spacing_m(double spacing_m);

/// Computes V_r at sites spread over `cloud` (one per `site_spacing_m` voxel: the point
/// nearest the voxel mean, with its normal). `cloud` needs unit normals pointing out of
/// the solid; points with a zero or non-finite normal do not become sites. Never throws.
IntegralInvariantResult compute_integral_invariants(const PointCloud& cloud,
                                                    const IntegralInvariantConfig& config);

}  // namespace anascan
