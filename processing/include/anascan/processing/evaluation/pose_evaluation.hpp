#pragma once
/// \file
/// Compares estimated scan poses with ground truth. Registration fixes poses only up to one
/// common rigid motion, so both sets are expressed in the frame of a reference scan (the
/// first scan present in both) before comparing.

#include <Eigen/Core>
#include <optional>
#include <string>
#include <vector>

#include "anascan/processing/core/pose.hpp"

namespace anascan {

/// A scan's pose by name (file name for .conf files).
struct NamedPose {
    std::string name;
    Pose T_world_scan;
    /// Truth only: the point of the scan (its own frame, metres) whose displacement is the
    /// translation error, e.g. the centroid of its points; default the frame's origin.
    Eigen::Vector3d measure_at_scan_m = Eigen::Vector3d::Zero();
};

/// Error of one scan relative to the reference scan.
struct ScanPoseError {
    std::string name;
    bool placed = false;         ///< False when the estimate lacks this scan.
    double rotation_deg = 0.0;   ///< Angle of the residual rotation, degrees.
    double translation_m = 0.0;  ///< Displacement of the truth's measure_at point, metres.
};

struct PoseEvaluation {
    std::string reference;             ///< Name of the scan both sets are expressed in.
    std::vector<ScanPoseError> scans;  ///< One per truth scan, in truth order.
    std::vector<std::string> unknown;  ///< Estimated scans absent from the truth.
    double max_rotation_deg = 0.0;     ///< Over placed scans.
    double max_translation_m = 0.0;    ///< Over placed scans.
    std::size_t placed = 0;
    /// The same maxima after the one rigid motion that best aligns the estimated measure
    /// points with the true ones (least squares over all placed scans, Umeyama) instead of
    /// the reference scan's frame: the common motion is then fixed by every scan, not by the
    /// reference's own error. Equal to the above with fewer than 3 placed scans.
    double max_rotation_best_fit_deg = 0.0;
    double max_translation_best_fit_m = 0.0;
};

/// Compares `estimated` with `truth`. Returns nullopt when they share no scan.
std::optional<PoseEvaluation> evaluate_poses(const std::vector<NamedPose>& estimated,
                                             const std::vector<NamedPose>& truth);

}  // namespace anascan
