#pragma once
/// \file
/// Coverage of a session's stone from its registered scans (the `anascan coverage` command,
/// the live figure of a capture session and the figure stored at its end).

#include <functional>
#include <optional>

#include "anascan/acquisition/store/groups.hpp"
#include "anascan/acquisition/store/session_store.hpp"
#include "anascan/processing/coverage/coverage.hpp"
#include "anascan/processing/planning/next_best_view.hpp"

namespace anascan::acquisition {

struct SessionCoverageConfig {
    /// Each scan is down-sampled to this voxel edge (metres) first; coverage bins points at
    /// CoverageConfig::bin_size_m anyway, so nothing finer is needed.
    double voxel_size_m = 0.002;
    CoverageConfig coverage{};
};

/// A scan reduced for coverage: voxel means, each standing for the captured points of its
/// voxel on average (density is counted in captured points).
struct CoverageCopy {
    PointCloud cloud;
    double points_per_point = 1.0;
    std::optional<Eigen::Vector3d> sensor_origin_scan_m;
};

CoverageCopy make_coverage_copy(const Scan& scan, double voxel_size_m);

/// Coverage from the registered, non-excluded scans of the session's largest group, in that
/// group's frame. kEmpty when no scan is registered. `progress(done, total)` may be empty.
Expected<CoverageReport> session_coverage(
    const SessionStore& store, const SessionCoverageConfig& config,
    const std::function<void(std::size_t, std::size_t)>& progress = {});

/// The scanner envelope of the session's device: that of its last scan's kind (a
/// time-of-flight station's, else structured light's).
ScannerEnvelope session_scanner_envelope(const SessionStore& store);

/// The next-best-view from the session's coverage (session_coverage), with the envelope of
/// the session's device unless `config` gives one (`use_session_device`).
struct SessionNextView {
    CoverageReport coverage;
    NextView view;
    double plan_s = 0.0;  ///< Time of the plan alone (the coverage before it not counted).
};
Expected<SessionNextView> session_next_view(const SessionStore& store,
                                            const SessionCoverageConfig& coverage_config,
                                            NextViewConfig config, bool use_session_device = true);

/// For a simulated session: the transform from the largest group's frame (where coverage and
/// the plan live) to the truth frame, from a registered scan with a true pose; nothing
/// without one. The simulated operator uses it to walk to a planned view, as an operator
/// reads the hint against the stone in front of them.
Expected<std::optional<Pose>> group_to_truth(const SessionStore& store);

}  // namespace anascan::acquisition
