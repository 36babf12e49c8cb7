#pragma once
/// \file
/// A fragment model against the true surface it was scanned from (a simulated stone's
/// mesh, or a reference scan): accuracy of the measured-class surface, completeness, and
/// whether the measured/interpolated classes agree with what the scanner could see from
/// its true poses. Both meshes must be in one frame (the caller aligns them). Used by
/// `anascan mesh eval`; docs/surface-reconstruction.md gives the figures.
///
/// Library code: no I/O, TBB loops, results independent of the thread count.

#include <Eigen/Core>
#include <cstddef>
#include <span>

#include "anascan/processing/core/mesh.hpp"
#include "anascan/processing/core/pose.hpp"
#include "anascan/processing/surface/fragment_model.hpp"

namespace anascan {

struct TruthComparisonConfig {
    double model_spacing_m = 2e-4;        ///< Samples on the model (accuracy).
    double truth_spacing_m = 5e-4;        ///< Samples on the truth (completeness).
    double completeness_within_m = 5e-4;  ///< A truth sample is covered within this.
};

/// Distances in metres; the quantiles are over area-uniform samples.
struct TruthComparison {
    std::size_t measured_samples = 0;  ///< Model samples on measured triangles.
    double measured_median_m = 0.0, measured_p95_m = 0.0, measured_max_m = 0.0;
    std::size_t interpolated_samples = 0;  ///< Model samples on interpolated triangles.
    double interpolated_median_m = 0.0, interpolated_p95_m = 0.0;
    std::size_t truth_samples = 0;
    double completeness = 0.0;  ///< Share of truth samples within completeness_within_m.
    /// Axis-aligned extents of the vertices in the common frame, metres.
    Eigen::Vector3d box_m = Eigen::Vector3d::Zero(), truth_box_m = Eigen::Vector3d::Zero();
};

/// Compares `model` (its triangles classed by `triangle_class`, or all measured when it is
/// empty) with `truth`.
TruthComparison compare_with_truth(const Mesh& model, std::span<const SurfaceClass> triangle_class,
                                   const Mesh& truth, const TruthComparisonConfig& config = {});

/// What a scanner could see from one of its true poses: a truth sample in its field of
/// view, within its depth range along the optical axis, facing it at an incidence within
/// the limit, and not hidden by the truth itself.
struct VisibilityConfig {
    double min_depth_m = 0.2, max_depth_m = 3.0;  ///< Along the optical axis (+z of the view).
    double horizontal_fov_deg = 180.0, vertical_fov_deg = 180.0;  ///< Full angles.
    double max_incidence_deg = 70.0;  ///< Truth normal against the direction to the sensor.
    double sample_spacing_m = 1e-3;   ///< Samples on the truth.
    /// A sample is matched to the model's class within this distance; farther samples
    /// (the model misses the surface there) count as interpolated.
    double match_within_m = 3e-3;
};

/// Truth area seen and never seen by the views, and how much of each the model classes
/// interpolated.
struct VisibilityAgreement {
    std::size_t samples = 0;
    double seen_area_m2 = 0.0, seen_interpolated_m2 = 0.0;
    double unseen_area_m2 = 0.0, unseen_interpolated_m2 = 0.0;
    /// Of the interpolated areas above, what has no model surface within match_within_m
    /// (the model is elsewhere there, e.g. a Poisson surface ballooning over an open side).
    double seen_missing_m2 = 0.0, unseen_missing_m2 = 0.0;
    double seen_interpolated_share() const;    ///< 0..1 (0 when nothing was seen).
    double unseen_interpolated_share() const;  ///< 0..1 (1 when everything was seen).
};

/// `views` are the sensors' true poses in the common frame (T_world_sensor: origin at the
/// optical centre, +z the optical axis, +x the image's columns). The truth's triangles face
/// outward (counter-clockwise seen from outside).
VisibilityAgreement compare_classes_with_visibility(const Mesh& model,
                                                    std::span<const SurfaceClass> triangle_class,
                                                    const Mesh& truth, std::span<const Pose> views,
                                                    const VisibilityConfig& config = {});

}  // namespace anascan
