#pragma once
/// \file
/// Registered poses against the simulator's true poses (simulated sessions only): both
/// sets are expressed in the frame of the first scan registered in the largest group, and
/// each translation error is measured at the scan's centroid (the scanner itself stands a
/// metre away, where a rotation error alone would dominate).

#include <optional>

#include "anascan/acquisition/store/session_store.hpp"
#include "anascan/processing/evaluation/pose_evaluation.hpp"

namespace anascan::acquisition {

/// Nothing when no registered scan has a true pose. Reads each compared scan once (for its
/// centroid). Scans registered in other groups count as not placed.
Expected<std::optional<PoseEvaluation>> evaluate_session_truth(const SessionStore& store);

}  // namespace anascan::acquisition
