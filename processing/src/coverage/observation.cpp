// Coverage, the criterion: a sample is observed when the captured points in a short
// cylinder under it (radius r along the surface, from depth_below into the stone to
// depth_above outside), counted only for scans whose sensor sees the sample at an
// incidence of at most max_incidence_deg, reach min_density over the cylinder's disc.
// Points of scans that see the sample from behind (incidence >= 90°) belong to another
// surface (the opposite face of a thin part) and are ignored.

#include <tbb/parallel_for.h>

#include <cmath>
#include <numbers>

#include "anascan/processing/spatial/kdtree.hpp"
#include "coverage/steps.hpp"

namespace anascan::coverage_detail {
namespace {

struct Sums {
    double good = 0.0;  // weight of points seen at a good incidence
    double seen = 0.0;  // weight of points seen from the front at any incidence
};

struct Criterion {
    float radius_sq, depth_below, depth_above, cos_max;
};

// Cosine of the incidence of `view` at sample (p, n); 1 when the sensor is unknown.
float incidence_cos(const BinnedPoints& points, std::uint32_t view, const Eigen::Vector3f& p,
                    const Eigen::Vector3f& n) {
    const Eigen::Vector3f& sensor = points.sensors[view];
    if (!sensor.allFinite()) return 1.0f;
    const Eigen::Vector3f to_sensor = sensor - p;
    const float length = to_sensor.norm();
    return length > 0.0f ? n.dot(to_sensor) / length : 0.0f;
}

Sums cylinder_sums(const BinnedPoints& points, const Criterion& c, const Eigen::Vector3f& p,
                   const Eigen::Vector3f& n, std::span<const Neighbor> neighbors) {
    Sums sums;
    for (const Neighbor& nb : neighbors) {
        const Eigen::Vector3f d = points.positions[nb.index] - p;
        const float along = n.dot(d);
        if (along < -c.depth_below || along > c.depth_above) continue;
        if (nb.distance_sq_m2 - along * along > c.radius_sq) continue;
        const float cos_inc = incidence_cos(points, points.views[nb.index], p, n);
        if (cos_inc <= 0.0f) continue;
        sums.seen += points.weights[nb.index];
        if (cos_inc >= c.cos_max) sums.good += points.weights[nb.index];
    }
    return sums;
}

}  // namespace

std::vector<SampleState> classify_samples(const SurfaceSamples& samples, const BinnedPoints& points,
                                          const CoverageConfig& config) {
    std::vector<SampleState> states(samples.positions.size(), SampleState::kUnobserved);
    if (points.size() == 0) return states;
    const KdTree tree(points.positions);
    const double r = config.cylinder_radius_m;
    const Criterion c{
        .radius_sq = static_cast<float>(r * r),
        .depth_below = static_cast<float>(config.depth_below_m),
        .depth_above = static_cast<float>(config.depth_above_m),
        .cos_max = static_cast<float>(std::cos(config.max_incidence_deg * std::numbers::pi / 180))};
    // A small sphere first (the cylinder's part near the surface): its sums are lower
    // bounds, so when they suffice the sample is observed; else the whole cylinder.
    const auto near_radius = static_cast<float>(std::sqrt(2.0 * r * r));
    const double depth = std::max(config.depth_below_m, config.depth_above_m);
    const auto full_radius = static_cast<float>(std::sqrt(r * r + depth * depth));
    const double needed = config.min_density_per_cm2 * std::numbers::pi * r * r * 1e4;
    tbb::parallel_for(tbb::blocked_range<std::size_t>(0, states.size(), 256), [&](auto range) {
        std::vector<Neighbor> neighbors;
        for (std::size_t i = range.begin(); i < range.end(); ++i) {
            const Eigen::Vector3f& p = samples.positions[i];
            const Eigen::Vector3f& n = samples.normals[i];
            tree.radius_any_order(p, near_radius, neighbors);
            Sums sums = cylinder_sums(points, c, p, n, neighbors);
            if (sums.good < needed && full_radius > near_radius) {
                tree.radius_any_order(p, full_radius, neighbors);
                sums = cylinder_sums(points, c, p, n, neighbors);
            }
            if (sums.good >= needed)
                states[i] = SampleState::kObserved;
            else if (sums.seen > 0.0)
                states[i] = SampleState::kSparse;
        }
    });
    return states;
}

}  // namespace anascan::coverage_detail
