#pragma once
/// \file
/// Whether each scan of a group stays where the rest of the group holds it. A scan placed by
/// links to one or two neighbours can slide along a face or an edge that fits anywhere along
/// it (the top and a long face of a block): every pair still agrees (crossing normals, free
/// space and offset are those of the true pose), yet fine registration of the scan against
/// all the others at once, where their relief fixes the slide, moves it away. This check
/// measures that pull for every scan; a scan pulled by far more than its fit's RMS is
/// reported, not moved (moving it changes what the scans registered after it rest on).
/// Pure geometry: no devices, no I/O. See docs/scan-registration.md "Union pull".
///
/// Thread safety: reentrant.

#include <cstddef>
#include <span>
#include <vector>

#include "anascan/processing/evaluation/group_consistency.hpp"
#include "anascan/processing/registration/fine/fine_registration.hpp"

namespace anascan {

struct UnionPullConfig {
    /// Each round starts from the last one's pose, until a round moves the scan's centroid by
    /// less than `settle_m` or `max_rounds` are done: one registration goes only part of the
    /// way along a slide (its gate shrinks with the RMS, small on sliding faces).
    FineRegistrationConfig fine{.max_correspondence_distance_m = 0.06,
                                .min_correspondence_distance_m = 0.003,
                                .max_iterations = 40,
                                .sample_count = 20000,
                                .overlap_distance_m = 0.003};
    int max_rounds = 8;
    double settle_m = 0.0002;
    /// Pulled: the centroid moves by more than this multiple of the final fit's RMS and
    /// more than `min_pull_m` (a true scan of the simulated small block moves by a few
    /// tenths of a millimetre; see the doc), to a better fit than where it was.
    double pull_rms_factor = 10.0;
    double min_pull_m = 0.002;
    double min_overlap_fraction = 0.3;  ///< Smaller overlaps with the rest are not judged.
};

struct ScanPull {
    double moved_m = 0.0;       ///< Centroid displacement from its pose in the group.
    double rotation_deg = 0.0;  ///< Rotation from its pose in the group.
    /// Point-to-plane RMS against the others over the points within the overlap distance,
    /// where the group put the scan and where they pull it.
    double rms_before_m = 0.0;
    double rms_m = 0.0;
    double overlap_fraction = 0.0;  ///< Where they pull it, within the overlap distance.
    int rounds = 0;
    bool judged = false;  ///< Enough overlap with the others to tell.
    bool pulled = false;
};

/// One entry per scan, in order. Scans need normals (sign free); fewer than 3 scans give
/// entries that are not judged (the others are one scan: pairwise agreement already says
/// all there is).
std::vector<ScanPull> union_pulls(std::span<const ConsistencyScan> scans,
                                  const UnionPullConfig& config = {});

}  // namespace anascan
