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
#include <vector>

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

/// One device a measurement needs, fixed on the sensor: a camera or a projector (origin at
/// its optical centre, +z its optical axis, +x its image's columns).
struct VisibilityDevice {
    Pose T_view_device = Pose::Identity();  ///< In the frame of the sensor's pose.
    double horizontal_fov_deg = 180.0, vertical_fov_deg = 180.0;  ///< Full angles.
};

/// What a scanner could measure from one of its true poses: a truth sample that every one
/// of its devices sees (a structured-light head measures a point only where both cameras
/// and the projector see it). A device sees a sample in its field of view, within the depth
/// range along its optical axis, not hidden by the truth itself, and facing it: the sample's
/// incidence from a view is the largest angle, over the devices, between its normal and the
/// direction to the device. A scanner's response fades with incidence rather than stopping
/// at one angle, so a sample is *seen* when some view has it within seen_incidence_deg,
/// *never seen* when no view has it within unseen_incidence_deg, and *grazing* between the
/// two (reported apart; equal limits leave no grazing band).
struct VisibilityConfig {
    double min_depth_m = 0.2, max_depth_m = 3.0;  ///< Along each device's optical axis.
    double seen_incidence_deg = 70.0;
    double unseen_incidence_deg = 80.0;
    double sample_spacing_m = 1e-3;  ///< Samples on the truth.
    /// A sample is matched to the model's class within this distance; farther samples
    /// (the model misses the surface there) count as interpolated.
    double match_within_m = 3e-3;
    /// A sample is covered by the model within this distance (completeness by class).
    double covered_within_m = 5e-4;
    /// Default: one device at the pose, seeing a half-space.
    std::vector<VisibilityDevice> devices{VisibilityDevice{}};
};

/// Truth area by its best view's incidence, and how much of it the model classes
/// interpolated: the scanner's response, read off the model.
struct IncidenceBand {
    double from_deg = 0.0, to_deg = 0.0;
    double area_m2 = 0.0, interpolated_m2 = 0.0;
};

/// Truth area seen, grazing and never seen by the views, and how much of each the model
/// classes interpolated.
struct VisibilityAgreement {
    std::size_t samples = 0;
    double seen_area_m2 = 0.0, seen_interpolated_m2 = 0.0;
    double grazing_area_m2 = 0.0, grazing_interpolated_m2 = 0.0;
    double unseen_area_m2 = 0.0, unseen_interpolated_m2 = 0.0;
    /// Of the interpolated areas above, what has no model surface within match_within_m
    /// (the model is elsewhere there, e.g. a Poisson surface ballooning over an open side).
    double seen_missing_m2 = 0.0, unseen_missing_m2 = 0.0;
    /// Area within covered_within_m of the model: completeness where the scanner saw,
    /// grazed and never saw the truth.
    double seen_covered_m2 = 0.0, grazing_covered_m2 = 0.0, unseen_covered_m2 = 0.0;
    /// From 0 to 90 degrees in 5 degree steps, then one band for the samples no view sees
    /// (out of every view's field, range or line of sight, or facing away): from 90 to 180.
    std::vector<IncidenceBand> bands;
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
