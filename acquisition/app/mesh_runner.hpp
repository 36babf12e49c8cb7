#pragma once
// Shared by `mesh` and `session export --mesh`: load placed scans, reconstruct the fragment
// model, write the mesh and its report, print the report table.
#include <CLI/CLI.hpp>
#include <string>
#include <vector>

#include "anascan/acquisition/assembly/mesh_scans.hpp"

namespace anascan::cli {

using MeshScanEntry = acquisition::MeshScan;

struct MeshOptions {
    std::string out;     ///< .ply, .obj or .stl
    std::string report;  ///< .json, optional
    double resolution_mm = 1.0;
    std::string surface = "closed";  ///< closed | measured
    bool ascii = false;              ///< ASCII PLY
    double max_memory_mb = 1536.0;
    bool poisson_vertices = false;  ///< Keep Poisson's vertices (no fit to the points).
    double octree_cell_factor = SurfaceConfig{}.octree_cell_factor;
};

/// Runs the whole job; throws CommandFailed with a message naming the file on bad input.
void run_mesh(const std::vector<MeshScanEntry>& entries, const MeshOptions& options);

/// Adds --resolution-mm, --surface, --report, --ascii, --max-memory-mb and
/// --poisson-vertices, --octree-cell-factor to `cmd`.
void add_mesh_options(CLI::App* cmd, MeshOptions& options);

/// Processor time of this process so far (all threads, user + system), seconds.
double processor_seconds();

/// Peak resident memory of this process so far, bytes.
std::size_t peak_memory_bytes();

}  // namespace anascan::cli
