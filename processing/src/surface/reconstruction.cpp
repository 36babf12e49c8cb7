#include "anascan/processing/surface/reconstruction.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <string>

#include "anascan/processing/core/stopwatch.hpp"
#include "anascan/processing/spatial/kdtree.hpp"
#include "anascan/processing/spatial/voxel_grid.hpp"
#include "anascan/processing/surface/mesh_topology.hpp"
#include "fit_to_points.hpp"
#include "merge.hpp"
#include "poisson.hpp"
#include "subdivide.hpp"
#include "support.hpp"

namespace anascan {
namespace {

using surface_detail::MergedCloud;

constexpr std::size_t kMinPoints = 16;

void say(const SurfaceProgress& progress, const std::string& message) {
    if (progress) progress(message);
}

double bounding_cube_m(const PointCloud& cloud) {
    const Bounds b = local_bounds(cloud);
    return static_cast<double>(b.extent().maxCoeff());
}

// Closed mode keeps the largest component: Poisson leaves small detached shells where
// samples are sparse, which are not part of the stone.
std::size_t keep_largest_component(FragmentModel& model) {
    const MeshTopology topo = analyse_topology(model.mesh);
    if (topo.components <= 1) return 0;
    std::vector<bool> keep(model.mesh.triangles.size());
    for (std::size_t t = 0; t < keep.size(); ++t) keep[t] = topo.triangle_component[t] == 0;
    model = select_triangles(model, keep);
    return topo.components - 1;
}

std::size_t drop_interpolated(FragmentModel& model) {
    std::vector<bool> keep(model.mesh.triangles.size());
    std::size_t dropped = 0;
    for (std::size_t t = 0; t < keep.size(); ++t) {
        keep[t] = model.triangle_class[t] == SurfaceClass::kMeasured;
        dropped += !keep[t];
    }
    model = select_triangles(model, keep);
    return dropped;
}

SurfaceStatus merge_and_orient(std::span<const PlacedScan> scans, const SurfaceConfig& config,
                               MergedCloud& merged, SurfaceResult& result,
                               const SurfaceProgress& progress) {
    SurfaceDiagnostics& d = result.diagnostics;
    Stopwatch watch;
    merged = surface_detail::merge_scans(scans, config.resolution_m);
    d.input_points = merged.input_points;
    d.merged_points = merged.cloud.size();
    d.seconds_merge = watch.seconds();
    if (merged.extent_too_large) return SurfaceStatus::kExtentTooLarge;
    if (d.input_points == 0) return SurfaceStatus::kNoPoints;
    if (d.merged_points < kMinPoints) return SurfaceStatus::kTooFewPoints;
    d.isolated_scans = merged.isolated_scans;
    if (!merged.isolated_scans.empty()) return SurfaceStatus::kIsolatedScan;
    for (const PlacedScan& s : scans) d.scans_with_sensor += s.sensor_world_m.has_value();
    say(progress, "normals on " + std::to_string(d.merged_points) + " merged points");
    watch.restart();
    d.normals_unoriented =
        surface_detail::orient_merged_normals(merged, scans, config.normal_k_neighbors);
    d.spacing_m = surface_detail::median_spacing(merged.cloud);
    d.seconds_normals = watch.seconds();
    return SurfaceStatus::kOk;
}

// Poisson on the merged points, or on a thinned copy (poisson_sample_cells).
Expected<Mesh> poisson_on_samples(const PointCloud& merged,
                                  const surface_detail::PoissonDepth& depth,
                                  const SurfaceConfig& config, SurfaceDiagnostics& d) {
    const surface_detail::PoissonParams params{.depth = depth.depth,
                                               .scale = config.poisson_scale,
                                               .threads = config.poisson_threads,
                                               .linear_fit = config.poisson_linear_fit};
    const double voxel_m = config.poisson_sample_cells * depth.cell_m;
    if (voxel_m <= config.resolution_m) {
        d.poisson_samples = merged.size();
        return surface_detail::poisson_surface(merged, params);
    }
    const PointCloud thinned = voxel_downsample(merged, {.voxel_size_m = voxel_m});
    d.poisson_samples = thinned.size();
    return surface_detail::poisson_surface(thinned, params);
}

// Each split halves the edges: the mesh is split while its cells are still at least twice
// the requested resolution, and fitting the new vertices to the points then recovers what
// the coarse cells rounded off (arrises, chips).
int subdivisions_for(double cell_m, double resolution_m) {
    return std::max(0, static_cast<int>(std::floor(std::log2(cell_m / resolution_m))));
}

}  // namespace

SurfaceResult reconstruct_surface(std::span<const PlacedScan> scans, const SurfaceConfig& config,
                                  const SurfaceProgress& progress) {
    SurfaceResult result;
    SurfaceDiagnostics& d = result.diagnostics;
    MergedCloud merged;
    result.status = merge_and_orient(scans, config, merged, result, progress);
    if (result.status != SurfaceStatus::kOk) return result;
    const double box_m = bounding_cube_m(merged.cloud) * config.poisson_scale;
    const double finest_cell_m = config.resolution_m * config.octree_cell_factor;
    const surface_detail::PoissonDepth depth = surface_detail::choose_depth(
        box_m, finest_cell_m, config.resolution_m, d.merged_points, config.max_memory_bytes);
    d.poisson_depth = depth.depth;
    d.cell_m = depth.cell_m;
    d.estimated_memory_bytes = depth.estimated_memory_bytes;
    char line[160];
    std::snprintf(line, sizeof(line), "screened Poisson: depth %d (cell %.2f mm, estimate %.0f MB)",
                  depth.depth, 1e3 * depth.cell_m,
                  double(depth.estimated_memory_bytes) / 1048576.0);
    say(progress, line);
    Stopwatch watch;
    auto poisson = poisson_on_samples(merged.cloud, depth, config, d);
    d.seconds_poisson = watch.seconds();
    if (!poisson) d.poisson_error = poisson.error().message;
    if (poisson) result.model.mesh = std::move(*poisson);
    if (result.model.mesh.triangles.empty()) {
        result.status = SurfaceStatus::kPoissonFailed;
        return result;
    }
    say(progress, "support of " + std::to_string(result.model.mesh.vertices.size()) + " vertices");
    watch.restart();
    const double spacing = std::max(d.spacing_m, config.resolution_m * 0.5);
    const double support_m = config.measured_spacing_factor * spacing;
    const KdTree tree(merged.cloud.positions);
    if (config.fit_to_points) {
        d.subdivisions = subdivisions_for(d.cell_m, config.resolution_m);
        for (int k = 0; k < d.subdivisions; ++k)
            result.model.mesh = surface_detail::subdivide_midpoints(result.model.mesh);
        const auto fit = surface_detail::fit_vertices_to_points(result.model.mesh, merged.cloud,
                                                                tree, support_m, 0.5 * support_m);
        d.vertices_fitted = fit.moved;
        d.median_fit_shift_m = fit.median_shift_m;
    }
    surface_detail::classify_support(result.model, merged, tree, support_m);
    if (config.mode == SurfaceMode::kClosed) {
        d.components_removed = keep_largest_component(result.model);
    } else {
        d.triangles_removed = drop_interpolated(result.model);
    }
    colour_by_class(result.model);
    d.seconds_support = watch.seconds();
    result.merged = std::move(merged.cloud);
    return result;
}

std::string_view to_string(SurfaceStatus status) {
    switch (status) {
        case SurfaceStatus::kOk:
            return "ok";
        case SurfaceStatus::kNoPoints:
            return "no finite points";
        case SurfaceStatus::kTooFewPoints:
            return "too few points for a surface";
        case SurfaceStatus::kIsolatedScan:
            return "a scan shares no surface with the others (wrong pose?)";
        case SurfaceStatus::kExtentTooLarge:
            return "the points spread too far for the resolution (a scan far from the others?)";
        case SurfaceStatus::kPoissonFailed:
            return "the Poisson solver produced no surface";
    }
    return "unknown";
}

}  // namespace anascan
