#pragma once
/// \file
/// Free-space check of a relative pose between two scans whose sensor positions are known.
/// A scanner that measured a surface at depth d along a ray saw empty space in front of it:
/// under a wrong pose (a box turned by 90° or 180° fits its look-alike faces) the
/// other scan's points land in that empty space (the block's faces differ in size, the
/// ground cuts through), under the true pose only noise and edges do. The scanned scan's
/// view is a depth image of its own points seen from its sensor position (a virtual pinhole
/// camera looking along their mean direction, bins of about two sample spacings); a point
/// of the other scan projected into it is a violation when it lies more than a tolerance in
/// front of the nearest surface of its bin and the bins around it. Points outside the
/// view (no surface in those bins) or behind the surface (occluded) say nothing.
/// See docs/scan-registration.md "Free-space check".
///
/// Thread safety: all functions are reentrant.

#include <Eigen/Core>
#include <cstddef>

#include "anascan/processing/core/point_cloud.hpp"
#include "anascan/processing/core/pose.hpp"

namespace anascan {

struct FreeSpaceConfig {
    /// Depth-image bin edge, in sample spacings of the viewed scan (at its median depth).
    double bin_spacing_factor = 2.0;
    /// A point is in free space when it lies more than this many sample spacings in front
    /// of the nearest surface of its bin's neighbourhood (fine registration leaves about a
    /// spacing of residual on true poses; noise and outliers add a little).
    double tolerance_spacing_factor = 4.0;
    std::size_t max_samples = 5000;  ///< Points of the other scan examined (evenly by index).
    /// Pairwise verification rejects a pose when more than this fraction of the examined
    /// points that fall in the view (on, behind or in front of its surface) lies in free
    /// space. Measured at true poses (docs/scan-registration.md "Free-space check"): bunny
    /// pairs 0-0.017, the 24-view structured-light session's neighbours 0-0.028, ray-cast
    /// block pairs 0; look-alike poses of the ray-cast block 0.05-0.23.
    double max_violation_fraction = 0.05;
    /// ... counted only when at least this many examined points fall in the view.
    std::size_t min_points_in_view = 50;
};

/// Figures of the points of one scan seen from the other scan's sensor.
struct FreeSpaceResult {
    bool valid = false;               ///< False: no view could be built (empty, sensor behind).
    std::size_t samples = 0;          ///< Points examined.
    std::size_t in_view = 0;          ///< Of those, projected onto the viewed scan's surface.
    std::size_t violations = 0;       ///< Of those, in front of it (free space).
    double violation_fraction = 0.0;  ///< violations / in_view (0 when nothing in view).
};

/// Examines `other`'s points, mapped by `T_viewed_other` into `viewed`'s frame, against the
/// view of `viewed` from `viewpoint_m` (its sensor position in its own frame, metres, as a
/// cloud position: origin included). `spacing_m` is viewed's median sample spacing (0:
/// computed here).
FreeSpaceResult check_free_space(const PointCloud& viewed, const Eigen::Vector3d& viewpoint_m,
                                 double spacing_m, const PointCloud& other,
                                 const Pose& T_viewed_other, const FreeSpaceConfig& config);

}  // namespace anascan
