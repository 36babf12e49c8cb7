#include "anascan/sim/surface_distance.hpp"

#include <tbb/parallel_for.h>

#include <algorithm>
#include <cmath>

namespace anascan::sim {

std::vector<double> surface_distances(const PointCloud& cloud, const Pose& T_mesh_cloud,
                                      const RayCaster& mesh, double max_distance_m) {
    std::vector<double> d(cloud.size(), max_distance_m);
    tbb::parallel_for(std::size_t{0}, cloud.size(), [&](std::size_t i) {
        if (const auto nearest =
                mesh.closest_point(T_mesh_cloud * cloud.world_position(i), max_distance_m))
            d[i] = nearest->distance_m;
    });
    return d;
}

SurfaceDistanceSummary summarize_distances(std::vector<double> d, double tolerance_m,
                                           double max_distance_m) {
    SurfaceDistanceSummary s{.points = d.size()};
    if (d.empty()) return s;
    std::sort(d.begin(), d.end());
    const std::size_t best = std::max<std::size_t>(d.size() * 95 / 100, 1);
    double sum2 = 0.0, sum2_best = 0.0;
    for (std::size_t i = 0; i < d.size(); ++i) {
        sum2 += d[i] * d[i];
        if (i < best) sum2_best += d[i] * d[i];
    }
    const auto count_above = [&](double x) {
        return std::size_t(d.end() - std::lower_bound(d.begin(), d.end(), x));
    };
    s.beyond_max = count_above(max_distance_m);
    s.within_fraction =
        1.0 - double(count_above(std::nextafter(tolerance_m, INFINITY))) / double(d.size());
    s.median_m = d[d.size() / 2];
    s.rms_m = std::sqrt(sum2 / double(d.size()));
    s.rms_best95_m = std::sqrt(sum2_best / double(best));
    return s;
}

}  // namespace anascan::sim
