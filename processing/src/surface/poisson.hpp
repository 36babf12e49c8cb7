#pragma once
// Screened Poisson surface reconstruction through Open3D 0.16 (a port of Kazhdan's
// PoissonRecon), in a module loaded on first use (open3d_poisson_module.cpp).
#include <cstddef>

#include "anascan/processing/core/expected.hpp"
#include "anascan/processing/core/mesh.hpp"

namespace anascan::surface_detail {

struct PoissonDepth {
    int depth = 0;        ///< Octree depth.
    double cell_m = 0.0;  ///< Finest cell width at that depth, metres.
    std::size_t estimated_memory_bytes = 0;
};

/// The depth whose finest cell is at most `finest_cell_m`, coarsened until Poisson's memory
/// estimate for `points` samples `resolution_m` apart fits `max_memory_bytes`.
PoissonDepth choose_depth(double box_m, double finest_cell_m, double resolution_m,
                          std::size_t points, std::size_t max_memory_bytes);

struct PoissonParams {
    int depth = 8;
    double scale = 1.1;  ///< The box relative to the points' bounding cube.
    int threads = 1;
    bool linear_fit = false;
};

/// The module's file name; it is looked for in $ANASCAN_POISSON_MODULE, beside the running
/// program, then where the build put it.
inline constexpr const char* kModuleName = "libanascan_open3d_poisson.so";

/// Runs screened Poisson on `cloud` (positions and unit normals). Returns the mesh in the
/// cloud's frame (same origin) with vertex normals, empty when the solver made no surface;
/// kIo error naming the module when it cannot be loaded.
Expected<Mesh> poisson_surface(const PointCloud& cloud, const PoissonParams& params);

}  // namespace anascan::surface_detail
