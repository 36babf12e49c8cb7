#pragma once
// Internal steps of coverage.cpp (not installed).

#include <Eigen/Core>
#include <cstdint>
#include <optional>
#include <span>
#include <vector>

#include "anascan/processing/cleaning/plane_removal.hpp"
#include "anascan/processing/core/mesh.hpp"
#include "anascan/processing/coverage/coverage.hpp"

namespace anascan::coverage_detail {

/// A voxel's integer cell packed into 64 bits (21 bits per axis, cells within ±2^20).
inline std::uint64_t pack_cell(const Eigen::Vector3i& cell) {
    constexpr std::int64_t kOffset = std::int64_t{1} << 20;
    constexpr std::uint64_t kMask = (std::uint64_t{1} << 21) - 1;
    std::uint64_t key = 0;
    for (int a = 0; a < 3; ++a)
        key = (key << 21) | (static_cast<std::uint64_t>(cell[a] + kOffset) & kMask);
    return key;
}

/// Every scan binned into voxels (count kept), in the world frame relative to origin_m.
struct BinnedPoints {
    Eigen::Vector3d origin_m = Eigen::Vector3d::Zero();
    std::vector<Eigen::Vector3f> positions;  ///< Mean of each bin, relative to origin_m.
    std::vector<float> weights;              ///< Captured points in the bin.
    std::vector<std::uint32_t> views;        ///< Index of the scan view.
    /// Per view: sensor position relative to origin_m (NaN when unknown).
    std::vector<Eigen::Vector3f> sensors;
    /// Per view: [begin, end) of its bins in the arrays above.
    std::vector<std::pair<std::size_t, std::size_t>> ranges;

    std::size_t size() const { return positions.size(); }
};

/// Bins every view (at most max_points_per_view of its points, evenly spaced in its order,
/// each standing for the ones skipped); views are processed in parallel, the result is in
/// view order.
BinnedPoints bin_views(std::span<const CoverageScanView> scans, const CoverageConfig& config);

/// The bins whose index is in `keep` (increasing), ranges recomputed.
BinnedPoints select_bins(const BinnedPoints& points, std::span<const std::size_t> keep);

/// The bins that are stone: off each view's ground plane on the sensor's side, then the
/// connected cluster nearest the median point.
struct StoneBins {
    std::vector<std::size_t> indices;           ///< Increasing.
    std::vector<std::optional<Plane>> grounds;  ///< Per view, facing its sensor.
};
StoneBins stone_bins(const BinnedPoints& points, const CoverageConfig& config);

/// The points the hull is built on: the stone's bins and, as the stone rests on the ground,
/// their projections onto their view's ground (what is under a seen part is stone or unseen).
std::vector<Eigen::Vector3f> hull_input(const BinnedPoints& stone,
                                        std::span<const std::optional<Plane>> grounds);

/// Of the `candidates` (increasing bin indices), those in the cluster of occupied voxels
/// (cluster_voxel_m, at least min_cluster_voxel_points each, 26-connected) nearest the
/// candidates' median point; increasing.
std::vector<std::size_t> nearest_cluster(const BinnedPoints& points,
                                         std::span<const std::size_t> candidates,
                                         const CoverageConfig& config);

/// The convex hull of the points (relative frame), outward triangles; empty on failure.
Mesh convex_hull(std::span<const Eigen::Vector3f> points);

/// Area-weighted random samples of the mesh's triangles with their triangle normals.
struct SurfaceSamples {
    std::vector<Eigen::Vector3f> positions;  ///< Same frame as the mesh's local positions.
    std::vector<Eigen::Vector3f> normals;
    double surface_area_m2 = 0.0;
};
SurfaceSamples sample_surface(const Mesh& mesh, double spacing_m, std::uint64_t seed);

/// The criterion for every sample (positions in the bins' relative frame).
std::vector<SampleState> classify_samples(const SurfaceSamples& samples, const BinnedPoints& points,
                                          const CoverageConfig& config);

/// Connected regions of samples not observed, largest first (positions relative to
/// origin_m, returned in world coordinates).
std::vector<CoverageHole> find_holes(const SurfaceSamples& samples,
                                     std::span<const SampleState> states,
                                     const Eigen::Vector3d& origin_m, const CoverageConfig& config);

}  // namespace anascan::coverage_detail
