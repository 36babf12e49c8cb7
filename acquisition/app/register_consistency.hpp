#pragma once
// `anascan register`: the placed scans checked against each other in their final poses
// (processing's check_group_consistency); a scan that contradicts the others is taken out.
#include <functional>
#include <string>
#include <vector>

#include "anascan/processing/core/expected.hpp"
#include "anascan/processing/core/point_cloud.hpp"
#include "anascan/processing/evaluation/group_consistency.hpp"
#include "anascan/processing/registration/batch/scan_registration.hpp"

namespace anascan::cli {

/// What the check found: how many placed scans it tested and took out.
struct RegisterConsistency {
    std::size_t checked = 0;
    std::size_t pairs = 0;
    std::size_t taken_out = 0;
};

/// Re-reads each placed scan with `load` (index into result.scans), reduces it to its own
/// density (about `target_points`), and checks the placed scans pairwise. A scan to take out
/// becomes not placed, its reason saying which scan it contradicts and by what figure.
RegisterConsistency check_placed_scans(ScanRegistrationResult& result,
                                       const std::function<Expected<PointCloud>(std::size_t)>& load,
                                       const std::optional<Eigen::Vector3d>& sensor_origin_scan_m,
                                       std::size_t target_points = 20000);

/// A scan reduced for the check: voxel from its own spacing to about `target_points`, fresh
/// normals (toward the sensor when known; the check ignores their sign otherwise).
PointCloud reduce_for_consistency(const PointCloud& cloud,
                                  const std::optional<Eigen::Vector3d>& sensor_origin_scan_m,
                                  std::size_t target_points = 20000);

/// One line per pair: its figures and verdict (names as given).
void print_pairs(const GroupConsistency& group, const std::vector<std::string>& names);

}  // namespace anascan::cli
