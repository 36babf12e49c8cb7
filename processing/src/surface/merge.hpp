#pragma once
// Merging registered scans on a grid, keeping for every merged point how many scans saw
// its cell and which scan's sensor to orient it toward.
#include <cstdint>
#include <optional>
#include <span>
#include <vector>

#include "anascan/processing/surface/reconstruction.hpp"

namespace anascan::surface_detail {

struct MergedCloud {
    PointCloud cloud;                         ///< One point per occupied cell (the mean), world.
    std::vector<std::uint16_t> scans;         ///< Distinct scans with a point in the cell.
    std::vector<std::uint32_t> first_scan;    ///< Lowest scan index in the cell.
    std::size_t input_points = 0;             ///< Finite input points.
    bool extent_too_large = false;            ///< The grid cannot index the points' extent.
    std::vector<std::size_t> isolated_scans;  ///< Scans sharing no cell with any other scan.
};

/// Merges the finite points of all scans on cubic cells of `cell_m`.
MergedCloud merge_scans(std::span<const PlacedScan> scans, double cell_m);

/// Orients the merged normals toward each point's first scan's sensor; where that scan has
/// none, consistently over the neighbour graph, with the overall sign that agrees with the
/// scans that have a sensor (outward when none has). Returns points left without a normal.
std::size_t orient_merged_normals(MergedCloud& merged, std::span<const PlacedScan> scans,
                                  int k_neighbors);

/// Median distance from each point to its nearest neighbour (metres), over a sample.
double median_spacing(const PointCloud& cloud);

}  // namespace anascan::surface_detail
