// What a scanner pose observes well: a sample inside the field of view, facing the sensor at
// an incidence within the criterion (less the planning margin), and close enough that the
// point density on it meets the criterion. The coverage surface is a convex hull, so a
// sample that faces the sensor is not hidden by the rest of the stone; the ground hides
// nothing above it, and the sensor never stands below it.

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include <cmath>
#include <numbers>

#include "planning/steps.hpp"

namespace anascan::planning_detail {
namespace {

double radians(double deg) { return deg * std::numbers::pi / 180.0; }

}  // namespace

ViewModel::ViewModel(const Candidate& candidate, const Eigen::Vector3d& up,
                     const NextViewConfig& config)
    : sensor_(candidate.sensor_m) {
    const Eigen::Vector3d axis = candidate.aim_m - candidate.sensor_m;
    if (axis.norm() < 1e-6) return;
    z_ = axis.normalized();
    const Eigen::Vector3d side = z_.cross(up);  // Image x: level, as a tripod holds it.
    if (side.norm() < 1e-6) return;             // Looking straight up or down: no roll.
    x_ = side.normalized();
    y_ = z_.cross(x_);
    const ScannerEnvelope& s = config.scanner;
    tan_half_h_ = std::tan(radians(0.5 * s.horizontal_fov_deg));
    tan_half_v_ = std::tan(radians(0.5 * s.vertical_fov_deg));
    cos_max_incidence_ =
        std::cos(radians(config.max_incidence_deg - config.planning_incidence_margin_deg));
    // Points per cm² on a surface at distance d and incidence θ: cos θ / (spacing_1m · d)²
    // · 1e-4; dense enough when cos θ / d² reaches this factor.
    density_factor_ = config.min_density_per_cm2 * s.spacing_at_1m_m * s.spacing_at_1m_m * 1e4;
    max_distance_sq_ = 1.0 / density_factor_;
    valid_ = density_factor_ > 0.0;
}

bool ViewModel::observes(const WantedSample& sample) const {
    const Eigen::Vector3d q = sample.position_m - sensor_;
    const double d_sq = q.squaredNorm();
    if (d_sq > max_distance_sq_ || d_sq < 1e-6) return false;
    const double depth = q.dot(z_);
    if (depth <= 0.0) return false;
    if (std::abs(q.dot(x_)) > depth * tan_half_h_ || std::abs(q.dot(y_)) > depth * tan_half_v_)
        return false;
    const double cos_incidence = -sample.normal.dot(q) / std::sqrt(d_sq);
    return cos_incidence >= cos_max_incidence_ && cos_incidence >= density_factor_ * d_sq;
}

std::vector<std::size_t> observed_by(const Candidate& candidate, const WantedSamples& wanted,
                                     const Eigen::Vector3d& up, const NextViewConfig& config) {
    std::vector<std::size_t> seen;
    const ViewModel view(candidate, up, config);
    if (!view.valid()) return seen;
    for (std::size_t i = 0; i < wanted.samples.size(); ++i)
        if (view.observes(wanted.samples[i])) seen.push_back(i);
    return seen;
}

ViewScore score_view(const Candidate& candidate, const WantedSamples& samples,
                     const Eigen::Vector3d& up, const NextViewConfig& config) {
    const ViewModel view(candidate, up, config);
    if (!view.valid()) return {};
    std::size_t wanted = 0, observed = 0;
    for (const WantedSample& s : samples.samples) wanted += view.observes(s) ? 1 : 0;
    for (const WantedSample& s : samples.observed) observed += view.observes(s) ? 1 : 0;
    return {samples.area_per_sample_m2 * static_cast<double>(wanted),
            samples.area_per_observed_m2 * static_cast<double>(observed)};
}

std::vector<bool> observable_by_any(std::span<const Candidate> candidates,
                                    const WantedSamples& wanted, const Eigen::Vector3d& up,
                                    const NextViewConfig& config) {
    std::vector<ViewModel> views;
    views.reserve(candidates.size());
    for (const Candidate& c : candidates) {
        ViewModel view(c, up, config);
        if (view.valid()) views.push_back(view);
    }
    std::vector<char> seen(wanted.samples.size(), 0);
    tbb::parallel_for(tbb::blocked_range<std::size_t>(0, seen.size(), 64),
                      [&](const tbb::blocked_range<std::size_t>& range) {
                          for (std::size_t i = range.begin(); i < range.end(); ++i)
                              for (const ViewModel& view : views)
                                  if (view.observes(wanted.samples[i])) {
                                      seen[i] = 1;
                                      break;
                                  }
                      });
    return {seen.begin(), seen.end()};
}

}  // namespace anascan::planning_detail
