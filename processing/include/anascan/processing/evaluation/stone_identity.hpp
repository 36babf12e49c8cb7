#pragma once
/// \file
/// Whether a scan can show the stone that a model of registered scans shows, from geometry
/// that does not depend on the scan's pose (the scan did not register, so its pose is
/// unknown). Two pose-free signals, each with its threshold from measured quantities:
///
///  - **Size.** The scan's width along its widest direction (the robust diameter: the
///    widest of many directions, each between low and high quantiles of the projections)
///    cannot exceed the stone's, that is the model's, beyond the sampling: the tolerance is
///    `width_noise_factor` × (sample spacing + noise) of the two clouds, both measured here,
///    plus how much one view of this stone was measured to exceed the rest of the model
///    (each model scan's width against the other model scans' together, the largest: a
///    model of few views misses some of the stone). It needs two model scans whose union is
///    wider than the widest of them by more than the noise tolerance (near-duplicate views
///    leave the rest of the stone unmeasured). A view of a
///    larger stone is caught; a view of a smaller one is not (a part of a stone is smaller
///    than the stone).
///  - **Surface.** The histograms of the integral-invariant volume descriptor (at four radii
///    from the measured spacing) of each scan: the new scan's distance to its nearest model
///    scan against the model's own spread (each model scan's distance to its nearest other
///    model scan, the largest of these). A scan farther than `surface_spread_factor` times
///    that spread, and farther than `min_surface_distance`, shows another kind of surface.
///    The second bound is there because a stone's faces differ (an ornament band on one,
///    clamp holes on another): a model of some faces does not measure how much the others
///    differ. An L1 distance of 1 means that the histograms share less than half their
///    mass: most of the scan's surface is of a kind no model scan shows.
///
/// No I/O, no sessions: the caller hands stone-only clouds (ground removed) with normals.

#include <cstddef>
#include <span>
#include <string>

#include "anascan/processing/core/point_cloud.hpp"

namespace anascan {

struct StoneIdentityConfig {
    std::size_t width_directions = 256;  ///< Directions on the half sphere for the widths.
    /// Fraction of the projections left out at each end of a width (stray points).
    double width_quantile = 0.002;
    /// The scan is wider than the stone when it exceeds the model's width by more than this
    /// many (spacing + noise) of the coarser cloud.
    double width_noise_factor = 4.0;
    std::size_t min_width_reference_scans = 2;  ///< The size signal needs this many model scans.
    std::size_t histogram_bins = 24;            ///< Bins of V_r over [0.2, 0.8] per radius.
    /// Another surface when the distance exceeds this multiple of the model's own spread.
    double surface_spread_factor = 2.0;
    /// ... and at least this L1 distance (of 2: the histograms share less than half).
    double min_surface_distance = 1.0;
    /// The surface signal needs at least this many model scans (the spread of one is none).
    std::size_t min_surface_reference_scans = 3;
    std::size_t max_samples = 4000;  ///< Points sampled for spacing and noise.
};

enum class StoneIdentityVerdict {
    kOtherStone,  ///< Size or surface says the scan shows another object.
    kLooksSame,   ///< Both signals fit the model (the usual case of the other side).
    kUndecided,   ///< Nothing says other; too few model scans to compare size or surface.
};

/// "other-stone", "looks-same", "undecided".
const char* to_string(StoneIdentityVerdict verdict);

struct StoneIdentityEvidence {
    StoneIdentityVerdict verdict = StoneIdentityVerdict::kUndecided;
    double scan_width_m = 0.0;   ///< The scan's widest width.
    double model_width_m = 0.0;  ///< The model's widest width (all model scans together).
    double width_tolerance_m = 0.0;
    double view_excess_m = -1.0;  ///< One view's largest excess over the rest; -1: unknown.
    double model_growth_m = 0.0;  ///< The model's width minus its widest scan's.
    double spacing_m = 0.0;       ///< Coarser median spacing of the scan and the model's scans.
    double noise_m = 0.0;         ///< Larger point-to-tangent-plane noise of them.
    /// L1 distance of descriptor histograms (0..2, mean over the radii); -1: not computed.
    double surface_distance = -1.0;
    double surface_spread = -1.0;  ///< Largest nearest-other distance among model scans.
    std::string reason;            ///< One line with the figures that decided.
};

/// Compares `scan` (its own frame) with the stone shown by `model_scans` (each in the
/// model's common frame: the widths need them together; the descriptors do not). Clouds
/// need unit normals (out of the solid, toward the sensor). Empty inputs: kUndecided.
StoneIdentityEvidence compare_with_stone(std::span<const PointCloud> model_scans,
                                         const PointCloud& scan,
                                         const StoneIdentityConfig& config = {});

/// The robust diameter of `clouds` taken together (see the file comment), metres.
double widest_width_m(std::span<const PointCloud* const> clouds, const StoneIdentityConfig& config);

}  // namespace anascan
