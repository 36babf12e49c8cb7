#pragma once
// Shared by `register` and `align`: the part of each scan to register (a box, a distance
// range) and the removal of a background plane (a wall or floor behind the object that
// would otherwise dominate the registration).
#include <CLI/CLI.hpp>
#include <string>
#include <vector>

#include "anascan/processing/core/point_cloud.hpp"

namespace anascan::cli {

struct RegionOptions {
    std::vector<double> box_m;    ///< XMIN YMIN ZMIN XMAX YMAX ZMAX, scan frame; empty: all.
    std::vector<double> range_m;  ///< MIN MAX distance from the scan frame's origin; empty: all.
    bool remove_background_plane = false;
};

/// Adds --roi-box, --roi-range-m and --remove-background-plane to `cmd`.
void add_region_options(CLI::App* cmd, RegionOptions& options);

/// The points of `cloud` inside the region, without the dominant plane when asked. Throws
/// CommandFailed naming `path` when no point is left.
PointCloud select_region(const PointCloud& cloud, const RegionOptions& region,
                         const std::string& path);

}  // namespace anascan::cli
