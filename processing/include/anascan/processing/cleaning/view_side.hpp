#pragma once
/// \file
/// The side a single range scan was seen from, without a sensor position. A range scan sees
/// every surface point from one side: its normals, oriented toward the sensor, all lie
/// within 90° of the viewing axis. The axis is the dominant direction of the unoriented
/// normals (the eigenvector of the largest eigenvalue of Σ n nᵀ); each normal is turned to
/// its side of the axis. Which end of the axis the sensor sat at is not fixed by the
/// normals (a height field looks the same from both sides); it is fixed by the prior that
/// the sensor was outside the solid: a scanned object shows its convex side, so the
/// oriented normals point, on average, away from the scan's centroid.
///
/// Library code: no I/O, no threads; reentrant.

#include <Eigen/Core>
#include <cstddef>

#include "anascan/processing/core/point_cloud.hpp"

namespace anascan {

struct ViewSideConfig {
    /// The convexity |mean n·(p − c)| below this fraction of the mean distance |p − c|
    /// leaves the end of the axis undecided (a flat scan); the sensor is then put on the
    /// side of +z of the local frame.
    double min_convexity_fraction = 1e-3;
};

struct ViewSideResult {
    bool oriented = false;  ///< Normals were present and at least one non-zero.
    /// Unit direction from the surface toward the estimated sensor side, local frame.
    Eigen::Vector3f view_direction = Eigen::Vector3f::UnitZ();
    /// Mean n·(p − c) of the oriented normals over the mean |p − c|: > 0 convex toward the
    /// view direction. Near 0 the end of the axis was a guess.
    double convexity = 0.0;
    bool decided = false;  ///< |convexity| reached the config's minimum.
    /// Fraction of non-zero normals within 84° of the axis (|n·a| > 0.1): near 1 for a range
    /// scan. It does not tell a merged or all-round cloud (about 0.9 for a sphere) from one
    /// scan: such a cloud needs its own normals or a sensor position.
    double facing_fraction = 0.0;
    std::size_t num_flipped = 0;  ///< Normals whose sign changed.
};

/// Orients `cloud.normals` (unit or zero, any signs) as seen from one side, estimated as
/// described in the file comment. Zero normals stay zero. Never throws.
ViewSideResult orient_as_range_scan(PointCloud& cloud, const ViewSideConfig& config = {});

}  // namespace anascan
