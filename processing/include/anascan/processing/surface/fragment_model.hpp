#pragma once
/// \file
/// A fragment model: a triangle mesh whose every vertex says how well it was measured and
/// whose every triangle is classed measured or interpolated (paper §4.3). A screened
/// Poisson surface closes every hole; this is what keeps a closed model honest about the
/// parts no scan saw.

#include <cstdint>
#include <span>
#include <vector>

#include "anascan/processing/core/mesh.hpp"

namespace anascan {

/// Whether a piece of the surface lies on measured points or was filled in.
enum class SurfaceClass : std::uint8_t {
    kMeasured = 0,      ///< Within the support threshold of measured points.
    kInterpolated = 1,  ///< Filled in by the reconstruction: nothing was measured there.
};

/// A mesh with per-vertex support and per-vertex / per-triangle class. Every vector is as
/// long as the mesh's vertices or triangles (checked by `consistent()`).
struct FragmentModel {
    Mesh mesh;  ///< World frame, metres; vertex normals outward, colours by class.
    /// Distance from each vertex to the nearest measured point, metres.
    std::vector<float> support_distance_m;
    /// Number of scans with a measured point within the support threshold of each vertex.
    std::vector<std::uint16_t> support_scans;
    std::vector<SurfaceClass> vertex_class;    ///< Per vertex.
    std::vector<SurfaceClass> triangle_class;  ///< Per triangle.
    double support_threshold_m = 0.0;          ///< Measured when support distance <= this.

    bool consistent() const;
};

/// Keeps the triangles for which `keep[t]` is true and the vertices they use (with their
/// attributes), renumbering the triangles.
FragmentModel select_triangles(const FragmentModel& model, const std::vector<bool>& keep);

/// The triangle classes of a mesh whose vertices carry a class: a triangle is measured when
/// at least two of its vertices are.
std::vector<SurfaceClass> triangle_classes_from_vertices(
    const Mesh& mesh, std::span<const SurfaceClass> vertex_class);

/// A class's colour (measured: stone grey, interpolated: orange), in files and on screen.
Rgb8 surface_class_color(SurfaceClass c);

/// Colours each vertex by its class (measured: stone grey, interpolated: orange), so that
/// any viewer shows what was filled in.
void colour_by_class(FragmentModel& model);

}  // namespace anascan
