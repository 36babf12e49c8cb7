#pragma once
// Per-vertex support (distance to the nearest measured point, scans that saw it) and the
// measured / interpolated class of vertices and triangles.
#include "anascan/processing/spatial/kdtree.hpp"
#include "anascan/processing/surface/fragment_model.hpp"
#include "merge.hpp"

namespace anascan::surface_detail {

/// Fills the support vectors and classes of `model` (whose mesh is in `merged.cloud`'s
/// frame). A vertex is measured when a merged point lies within `threshold_m`; a triangle
/// is measured when at least two of its vertices are. `tree` indexes `merged.cloud.positions`.
void classify_support(FragmentModel& model, const MergedCloud& merged, const KdTree& tree,
                      double threshold_m);

}  // namespace anascan::surface_detail
