#pragma once
/// \file
/// Fragment models from registered scans (paper §4.3): the scans are merged on a grid at
/// the requested resolution, normals are recomputed on the merged cloud and oriented with
/// each scan's sensor origin (consistently where a scan has none), screened Poisson
/// (Kazhdan and Hoppe 2013, Open3D's port) gives a watertight surface, and every vertex
/// and triangle is classed measured or interpolated from its distance to the measured
/// points. docs/surface-reconstruction.md gives the figures and the reasons.
///
/// Library code: no I/O, no threads of its own (TBB loops; Open3D's Poisson runs on one
/// thread unless `poisson_threads` says otherwise); results do not depend on the thread
/// count at the default.

#include <Eigen/Core>
#include <cstddef>
#include <functional>
#include <optional>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include "anascan/processing/core/expected.hpp"
#include "anascan/processing/core/point_cloud.hpp"
#include "anascan/processing/surface/fragment_model.hpp"

namespace anascan {

/// One registered scan: its points already in the common (world) frame.
struct PlacedScan {
    const PointCloud* cloud = nullptr;  ///< World frame; must outlive the call.
    /// Sensor position in the world frame, metres; nullopt when unknown.
    std::optional<Eigen::Vector3d> sensor_world_m;
};

/// `closed` keeps the watertight surface (interpolated parts flagged); `measured` removes
/// the interpolated triangles so that real holes stay open.
enum class SurfaceMode { kClosed, kMeasured };

struct SurfaceConfig {
    double resolution_m = 1e-3;  ///< Finest Poisson cell and merge grid, metres (> 0).
    SurfaceMode mode = SurfaceMode::kClosed;
    int normal_k_neighbors = 15;  ///< k-NN size of the normals on the merged cloud.
    /// A vertex is measured when a merged point lies within this many sampling spacings
    /// (median nearest-neighbour distance of the merged cloud).
    double measured_spacing_factor = 2.5;
    /// Poisson's memory budget, bytes: the octree is coarsened until its estimate fits.
    std::size_t max_memory_bytes = std::size_t(1536) << 20;
    double poisson_scale = 1.1;  ///< Poisson's box relative to the points' bounding cube.
    /// Threads of Poisson's own pool. 1 (the default) makes the surface independent of the
    /// machine and avoids the pool's per-slice barriers, which stall on a loaded machine.
    int poisson_threads = 1;
    /// Poisson's samples: the merged points thinned to one per cube of this many finest
    /// Poisson cells (0: every merged point). Support and accuracy use every merged point.
    double poisson_sample_cells = 0.0;
    /// Open3D's linear_fit: iso-vertices placed by linear interpolation of the implicit
    /// function instead of at the cell edges' midpoints.
    bool poisson_linear_fit = false;
    /// Moves the vertices near measured points onto the points' local surface (one face's
    /// points, Gaussian-weighted, within the support threshold): Poisson's octree rounds
    /// arrises and offsets faces by up to a cell. When the memory budget made the octree
    /// coarser than `resolution_m`, the mesh is first subdivided back to about it.
    bool fit_to_points = true;
    /// The octree's finest cell may be up to this many times `resolution_m`: the fit to the
    /// points, not the octree, gives the surface its detail (1 for Poisson's own detail).
    double octree_cell_factor = 2.0;
};

enum class SurfaceStatus {
    kOk,
    kNoPoints,        ///< No finite points in any scan.
    kTooFewPoints,    ///< Fewer than a surface needs.
    kIsolatedScan,    ///< A scan shares no grid cell with any other (see isolated_scans).
    kExtentTooLarge,  ///< The points spread beyond what the grid indexes at the resolution.
    kPoissonFailed,   ///< The solver returned no triangles.
};

/// What the reconstruction did, with figures for the report.
struct SurfaceDiagnostics {
    std::size_t input_points = 0;     ///< Finite points over all scans.
    std::size_t merged_points = 0;    ///< After merging on the grid.
    std::size_t poisson_samples = 0;  ///< Merged points Poisson was given.
    std::string poisson_error;        ///< Why the solver could not run (its module missing).
    std::size_t scans_with_sensor = 0;
    std::vector<std::size_t> isolated_scans;  ///< Indices of scans sharing no cell with others.
    std::size_t normals_unoriented = 0;       ///< Merged points whose normal could not be fitted.
    double spacing_m = 0.0;                   ///< Median nearest-neighbour distance, merged cloud.
    int poisson_depth = 0;                    ///< Octree depth used.
    double cell_m = 0.0;                      ///< Finest cell that depth gives, metres.
    std::size_t estimated_memory_bytes = 0;   ///< Poisson's estimate at that depth.
    std::size_t components_removed = 0;       ///< Small disconnected pieces dropped (closed mode).
    std::size_t triangles_removed = 0;        ///< Interpolated triangles dropped (measured mode).
    int subdivisions = 0;  ///< Midpoint subdivisions before the fit (octree coarser than asked).
    std::size_t vertices_fitted = 0;  ///< Vertices moved onto the points' surface.
    double median_fit_shift_m = 0.0;  ///< Their median move, metres.
    double seconds_merge = 0, seconds_normals = 0, seconds_poisson = 0, seconds_support = 0;
};

struct SurfaceResult {
    SurfaceStatus status = SurfaceStatus::kOk;
    FragmentModel model;
    SurfaceDiagnostics diagnostics;
    /// The merged, oriented cloud the surface was fitted to (support and accuracy use it).
    PointCloud merged;
};

/// Stage messages for long work ("normals on 412,345 merged points").
using SurfaceProgress = std::function<void(std::string_view message)>;

/// Reconstructs a fragment model from registered scans. Never throws on degenerate input:
/// empty, too few or non-finite points give a status.
SurfaceResult reconstruct_surface(std::span<const PlacedScan> scans, const SurfaceConfig& config,
                                  const SurfaceProgress& progress = {});

/// Short English name of a status, for messages and JSON.
std::string_view to_string(SurfaceStatus status);

}  // namespace anascan
