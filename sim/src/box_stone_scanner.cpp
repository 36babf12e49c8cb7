#include "anascan/sim/box_stone_scanner.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <numbers>
#include <optional>
#include <random>

#include "anascan/sim/viewpoints.hpp"

namespace anascan::sim {
namespace {

constexpr double kDegToRad = std::numbers::pi / 180.0;
// Rays are never cast further than this from the optical axis (a sensor's field of view).
constexpr double kMaxRayAngleRad = 80.0 * kDegToRad;
// A grid larger than this is a configuration mistake; such a view stays empty.
constexpr double kMaxRays = 1e9;

// T_world_sensor of view `view`: on a circle around the block's vertical (z) axis at
// `distance_m` from its centre, raised by `elevation_deg`; the sensor looks at the centre
// along its +z, with +x to the right and +y down (camera convention).
Pose sensor_pose(const BoxStoneScanConfig& config, int view) {
    return sensor_looking_at(Eigen::Vector3d::Zero(),
                             Viewpoint{.azimuth_deg = 360.0 * view / config.view_count,
                                       .elevation_deg = config.elevation_deg,
                                       .distance_m = config.distance_m});
}

// Angles of the ray grid: a ray at (ax, ay) has direction (tan ax, tan ay, 1), normalised,
// in the sensor frame.
struct AngularWindow {
    double x_min = 0.0, x_max = 0.0, y_min = 0.0, y_max = 0.0;
};

AngularWindow window_covering_box(const Eigen::Vector3d& half_m, const Pose& T_world_sensor) {
    AngularWindow w{INFINITY, -INFINITY, INFINITY, -INFINITY};
    const Pose T_sensor_world = T_world_sensor.inverse();
    for (int corner = 0; corner < 8; ++corner) {
        const Eigen::Vector3d signs((corner & 1) ? 1 : -1, (corner & 2) ? 1 : -1,
                                    (corner & 4) ? 1 : -1);
        const Eigen::Vector3d q = T_sensor_world * half_m.cwiseProduct(signs);
        const double ax = std::clamp(std::atan2(q.x(), q.z()), -kMaxRayAngleRad, kMaxRayAngleRad);
        const double ay = std::clamp(std::atan2(q.y(), q.z()), -kMaxRayAngleRad, kMaxRayAngleRad);
        w = {std::min(w.x_min, ax), std::max(w.x_max, ax), std::min(w.y_min, ay),
             std::max(w.y_max, ay)};
    }
    return w;
}

struct Hit {
    double range_m = 0.0;
    Eigen::Vector3d normal_world = Eigen::Vector3d::Zero();  ///< Faces the ray's origin.
};

// Slab test (Kay & Kajiya 1986) of a ray from outside against the box |p_i| <= half_i.
std::optional<Hit> intersect_box(const Eigen::Vector3d& half_m, const Eigen::Vector3d& origin,
                                 const Eigen::Vector3d& direction) {
    double t_near = -INFINITY, t_far = INFINITY;
    int entry_axis = -1;
    for (int a = 0; a < 3; ++a) {
        if (direction[a] == 0.0) {
            if (std::abs(origin[a]) > half_m[a]) return std::nullopt;
            continue;
        }
        double t0 = (-half_m[a] - origin[a]) / direction[a];
        double t1 = (half_m[a] - origin[a]) / direction[a];
        if (t0 > t1) std::swap(t0, t1);
        if (t0 > t_near) {
            t_near = t0;
            entry_axis = a;
        }
        t_far = std::min(t_far, t1);
    }
    if (entry_axis < 0 || t_near > t_far || t_near <= 0.0) return std::nullopt;
    Hit hit{.range_m = t_near};
    hit.normal_world[entry_axis] = direction[entry_axis] > 0.0 ? -1.0 : 1.0;
    return hit;
}

ScanMetadata view_metadata(int view, const Pose& T_world_sensor) {
    char id[32];
    std::snprintf(id, sizeof(id), "box-view-%02d", view);
    ScanMetadata meta;
    meta.id = id;
    meta.sequence = view;
    meta.device_id = "sim:box";
    meta.device_kind = DeviceKind::kStructuredLight;
    meta.sensor_origin_scan_m = Eigen::Vector3d::Zero();
    meta.T_world_scan = T_world_sensor;
    return meta;
}

// Gaussian range noise; none (and no random draws) for a non-positive sigma.
double draw_noise(double sigma_m, std::mt19937& rng) {
    if (!(sigma_m > 0.0)) return 0.0;
    return std::normal_distribution<double>(0.0, sigma_m)(rng);
}

// Casts the ray grid of one view; points and normals in the sensor frame.
PointCloud cast_rays(const BoxStoneScanConfig& config, const Pose& T_world_sensor,
                     std::mt19937& rng) {
    PointCloud cloud;
    const double step = config.angular_step_deg * kDegToRad;
    const Eigen::Vector3d half_m = 0.5 * config.size_m.cwiseAbs();
    const AngularWindow w = window_covering_box(half_m, T_world_sensor);
    const double cols = std::floor((w.x_max - w.x_min) / step) + 1.0;
    const double rows = std::floor((w.y_max - w.y_min) / step) + 1.0;
    if (!(step > 0.0) || !(cols * rows <= kMaxRays)) return cloud;
    const Eigen::Matrix3d R_sensor_world = T_world_sensor.linear().transpose();
    for (int row = 0; row < static_cast<int>(rows); ++row) {
        for (int col = 0; col < static_cast<int>(cols); ++col) {
            const Eigen::Vector3d ray_sensor =
                Eigen::Vector3d(std::tan(w.x_min + col * step), std::tan(w.y_min + row * step), 1.0)
                    .normalized();
            const auto hit = intersect_box(half_m, T_world_sensor.translation(),
                                           T_world_sensor.linear() * ray_sensor);
            if (!hit) continue;
            const double range_m = hit->range_m + draw_noise(config.noise_sigma_m, rng);
            cloud.positions.push_back((range_m * ray_sensor).cast<float>());
            cloud.normals.push_back((R_sensor_world * hit->normal_world).cast<float>());
        }
    }
    return cloud;
}

}  // namespace

std::vector<Scan> scan_box_stone(const BoxStoneScanConfig& config) {
    std::vector<Scan> scans;
    for (int view = 0; view < config.view_count; ++view) {
        const Pose T_world_sensor = sensor_pose(config, view);
        std::mt19937 rng(config.seed + static_cast<std::uint32_t>(view));
        scans.push_back(Scan{.meta = view_metadata(view, T_world_sensor),
                             .cloud = cast_rays(config, T_world_sensor, rng)});
    }
    return scans;
}

}  // namespace anascan::sim
