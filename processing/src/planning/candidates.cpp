// The samples the plan wants observed, and the scanner poses it evaluates: around each aim
// point (the largest holes' centres and the centre of everything unseen), a sphere of
// directions (azimuth steps around the stone's vertical, elevations from below the aim point
// to steeply above) at a few standoffs, kept when the operator can stand there.

#include <algorithm>
#include <cmath>
#include <numbers>

#include "planning/steps.hpp"

namespace anascan::planning_detail {
namespace {

struct FacePlane {
    Eigen::Vector3d normal;
    double offset_m;
};

std::vector<FacePlane> face_planes(const Mesh& surface) {
    std::vector<FacePlane> planes;
    planes.reserve(surface.triangles.size());
    for (const Eigen::Vector3i& t : surface.triangles) {
        const Eigen::Vector3d a = surface.vertices.world_position(static_cast<std::size_t>(t[0]));
        const Eigen::Vector3d b = surface.vertices.world_position(static_cast<std::size_t>(t[1]));
        const Eigen::Vector3d c = surface.vertices.world_position(static_cast<std::size_t>(t[2]));
        const Eigen::Vector3d n = (b - a).cross(c - a);
        if (n.norm() < 1e-12) continue;
        planes.push_back({n.normalized(), -n.normalized().dot(a)});
    }
    return planes;
}

// Of a convex surface: the largest signed distance to a face plane, a lower bound of the
// distance outside (negative inside).
double outside_distance_m(std::span<const FacePlane> planes, const Eigen::Vector3d& p) {
    double d = -std::numeric_limits<double>::infinity();
    for (const FacePlane& f : planes) d = std::max(d, f.normal.dot(p) + f.offset_m);
    return d;
}

std::vector<Eigen::Vector3d> aim_points(const CoverageReport& coverage, const WantedSamples& wanted,
                                        std::size_t max_holes) {
    std::vector<Eigen::Vector3d> aims;
    for (std::size_t h = 0; h < coverage.holes.size() && h < max_holes; ++h)
        aims.push_back(coverage.holes[h].centre_m);
    Eigen::Vector3d centre = Eigen::Vector3d::Zero();
    for (const WantedSample& s : wanted.samples) centre += s.position_m;
    if (!wanted.samples.empty())
        aims.push_back(centre / static_cast<double>(wanted.samples.size()));
    return aims;
}

// Within max_step_deg of a position the model was scanned from, seen from the centre.
class StepLimit {
public:
    StepLimit(const PlanningFrame& frame, const NextViewConfig& config)
        : centre_(frame.origin_world_m +
                  frame.R_stone_world.row(2).transpose() * 0.5 * frame.extent_m.z()),
          cos_max_(std::cos(config.max_step_deg * std::numbers::pi / 180.0)) {
        for (const Eigen::Vector3d& p : config.scanner_positions_world)
            if ((p - centre_).norm() > 1e-6) directions_.push_back((p - centre_).normalized());
    }
    bool allows(const Eigen::Vector3d& sensor) const {
        if (directions_.empty()) return true;
        const Eigen::Vector3d d = (sensor - centre_).normalized();
        for (const Eigen::Vector3d& known : directions_)
            if (d.dot(known) >= cos_max_) return true;
        return false;
    }

private:
    Eigen::Vector3d centre_;
    double cos_max_;
    std::vector<Eigen::Vector3d> directions_;
};

bool near_a_failed_view(const NextViewConfig& config, const Eigen::Vector3d& sensor) {
    for (const Eigen::Vector3d& p : config.failed_sensor_positions_world)
        if ((p - sensor).norm() < config.failed_view_radius_m) return true;
    return false;
}

double lerp_step(double from, double to, int i, int steps) {
    return steps <= 1 ? 0.5 * (from + to) : from + (to - from) * i / (steps - 1);
}

}  // namespace

namespace {

std::vector<WantedSample> thinned(const CoverageReport& coverage,
                                  std::span<const std::size_t> indices, std::size_t max_samples) {
    std::vector<WantedSample> out;
    const std::size_t stride = std::max<std::size_t>(
        1, (indices.size() + max_samples - 1) / std::max<std::size_t>(1, max_samples));
    for (std::size_t k = 0; k < indices.size(); k += stride)
        out.push_back({coverage.samples.world_position(indices[k]),
                       coverage.samples.normals[indices[k]].cast<double>().normalized()});
    return out;
}

}  // namespace

WantedSamples wanted_samples(const CoverageReport& coverage, std::size_t max_samples) {
    WantedSamples out;
    const std::size_t n = coverage.sample_states.size();
    if (n == 0 || coverage.samples.normals.size() != n) return out;
    std::vector<std::size_t> wanted, observed;
    for (std::size_t i = 0; i < n; ++i)
        (coverage.sample_states[i] == SampleState::kObserved ? observed : wanted).push_back(i);
    const double area_per_sample = coverage.surface_area_m2 / static_cast<double>(n);
    out.total_area_m2 = area_per_sample * static_cast<double>(wanted.size());
    out.samples = thinned(coverage, wanted, max_samples);
    out.observed = thinned(coverage, observed, max_samples);
    if (!out.samples.empty())
        out.area_per_sample_m2 = out.total_area_m2 / static_cast<double>(out.samples.size());
    if (!out.observed.empty())
        out.area_per_observed_m2 = area_per_sample * static_cast<double>(observed.size()) /
                                   static_cast<double>(out.observed.size());
    return out;
}

std::vector<Candidate> candidate_views(const CoverageReport& coverage, const WantedSamples& wanted,
                                       const PlanningFrame& frame, const NextViewConfig& config) {
    const std::vector<FacePlane> planes = face_planes(coverage.surface);
    const ScannerEnvelope& s = config.scanner;
    const Eigen::Matrix3d R_world_stone = frame.R_stone_world.transpose();
    const StepLimit step_limit(frame, config);
    std::vector<Candidate> out;
    for (const Eigen::Vector3d& aim : aim_points(coverage, wanted, config.max_aim_points))
        for (int e = 0; e < config.elevation_steps; ++e) {
            const double el =
                lerp_step(-15.0, 75.0, e, config.elevation_steps) * std::numbers::pi / 180.0;
            for (int a = 0; a < config.azimuth_steps; ++a) {
                const double az = 2.0 * std::numbers::pi * a / config.azimuth_steps;
                const Eigen::Vector3d dir =
                    R_world_stone * Eigen::Vector3d(std::cos(el) * std::cos(az),
                                                    std::cos(el) * std::sin(az), std::sin(el));
                for (int k = 0; k < config.standoff_steps; ++k) {
                    const double standoff =
                        lerp_step(s.min_standoff_m, s.max_standoff_m, k, config.standoff_steps);
                    const Eigen::Vector3d sensor = aim + standoff * dir;
                    const Eigen::Vector3d local = frame.to_stone(sensor);
                    if (local.z() < s.min_height_m || local.z() > s.max_height_m) continue;
                    if (local.head<2>().norm() > s.max_radius_m) continue;
                    if (!planes.empty() && outside_distance_m(planes, sensor) < s.min_clearance_m)
                        continue;
                    if (!step_limit.allows(sensor)) continue;
                    if (near_a_failed_view(config, sensor)) continue;
                    out.push_back({sensor, aim, standoff, local.z()});
                }
            }
        }
    return out;
}

}  // namespace anascan::planning_detail
