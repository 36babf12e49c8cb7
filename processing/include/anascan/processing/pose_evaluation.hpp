#pragma once
/// \file
/// Compares estimated scan poses with ground truth. Registration fixes poses only up to one
/// common rigid motion, so both sets are expressed in the frame of a reference scan (the
/// first scan present in both) before comparing.

#include <optional>
#include <string>
#include <vector>

#include "anascan/processing/pose.hpp"

namespace anascan {

/// A scan's pose by name (file name for .conf files).
struct NamedPose {
    std::string name;
    Pose T_world_scan;
};

/// Error of one scan relative to the reference scan.
struct ScanPoseError {
    std::string name;
    bool placed = false;         ///< False when the estimate lacks this scan.
    double rotation_deg = 0.0;   ///< Angle of the residual rotation, degrees.
    double translation_m = 0.0;  ///< Distance between the positions, metres.
};

struct PoseEvaluation {
    std::string reference;             ///< Name of the scan both sets are expressed in.
    std::vector<ScanPoseError> scans;  ///< One per truth scan, in truth order.
    std::vector<std::string> unknown;  ///< Estimated scans absent from the truth.
    double max_rotation_deg = 0.0;     ///< Over placed scans.
    double max_translation_m = 0.0;    ///< Over placed scans.
    std::size_t placed = 0;
};

/// Compares `estimated` with `truth`. Returns nullopt when they share no scan.
std::optional<PoseEvaluation> evaluate_poses(const std::vector<NamedPose>& estimated,
                                             const std::vector<NamedPose>& truth);

}  // namespace anascan
