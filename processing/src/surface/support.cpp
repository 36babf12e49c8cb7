#include "support.hpp"

#include <tbb/parallel_for.h>

#include <algorithm>
#include <cmath>
#include <limits>

namespace anascan::surface_detail {

void classify_support(FragmentModel& model, const MergedCloud& merged, const KdTree& tree,
                      double threshold_m) {
    const PointCloud& v = model.mesh.vertices;
    const std::size_t n = v.size();
    model.support_threshold_m = threshold_m;
    model.support_distance_m.assign(n, std::numeric_limits<float>::infinity());
    model.support_scans.assign(n, 0);
    model.vertex_class.assign(n, SurfaceClass::kInterpolated);
    const Eigen::Vector3f shift = (v.origin_m - merged.cloud.origin_m).cast<float>();
    const float radius = static_cast<float>(threshold_m);
    tbb::parallel_for(tbb::blocked_range<std::size_t>(0, n, 1024), [&](const auto& range) {
        std::vector<Neighbor> near;
        for (std::size_t i = range.begin(); i != range.end(); ++i) {
            const Eigen::Vector3f q = v.positions[i] + shift;
            Neighbor nn;
            if (tree.nearest(q, nn)) model.support_distance_m[i] = std::sqrt(nn.distance_sq_m2);
            tree.radius_any_order(q, radius, near);
            std::uint16_t scans = 0;
            for (const Neighbor& p : near) scans = std::max(scans, merged.scans[p.index]);
            model.support_scans[i] = scans;
            if (model.support_distance_m[i] <= radius)
                model.vertex_class[i] = SurfaceClass::kMeasured;
        }
    });
    model.triangle_class = triangle_classes_from_vertices(model.mesh, model.vertex_class);
}

}  // namespace anascan::surface_detail
