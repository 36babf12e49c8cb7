#pragma once
// A simulated operator for live registration tests: viewpoints around a block (turned over
// halfway), a cheap pinhole ray-cast scanner, and the errors of registered poses against the
// truth expressed in the block frame of the first placement.

#include <Eigen/Geometry>
#include <cmath>
#include <cstdint>
#include <map>
#include <memory>
#include <random>
#include <utility>
#include <vector>

#include "anascan/processing/core/point_cloud.hpp"
#include "anascan/processing/core/pose.hpp"
#include "anascan/sim/ray_caster.hpp"
#include "anascan/sim/scene.hpp"
#include "anascan/sim/viewpoints.hpp"

namespace anascan::testing {

/// One planned capture: where the sensor stands and how the block lies.
struct PlannedView {
    sim::Viewpoint view;
    sim::BlockPlacement placement;
    bool turned_over_before = false;  ///< First view after the flip.
};

/// `views_per_side` views around the block at 1.0-1.2 m, azimuth steps of 360/views_per_side,
/// elevation alternating 30°/50°, small jitter; then the block turned over (resting on +z),
/// yawed by `flip_yaw_deg` more and moved a few centimetres, and the same tour again.
inline std::vector<PlannedView> plan_tour(int views_per_side, const sim::BlockPlacement& first,
                                          std::uint32_t seed, double flip_yaw_deg = 20.0) {
    std::mt19937 rng(seed);
    std::uniform_real_distribution<double> jitter(-1.0, 1.0);
    sim::BlockPlacement turned = first;
    turned.resting_face = sim::BlockFace::kPosZ;
    turned.yaw_deg += flip_yaw_deg;
    turned.position_m += Eigen::Vector2d(0.03, -0.02);
    std::vector<PlannedView> plan;
    for (int side = 0; side < 2; ++side) {
        for (int k = 0; k < views_per_side; ++k) {
            PlannedView p;
            p.view.azimuth_deg = 30.0 + k * 360.0 / views_per_side + 3.0 * jitter(rng);
            p.view.elevation_deg = (k % 2 == 0 ? 30.0 : 50.0) + 3.0 * jitter(rng);
            p.view.distance_m = 1.1 + 0.08 * jitter(rng);
            p.placement = side == 0 ? first : turned;
            p.turned_over_before = side == 1 && k == 0;
            plan.push_back(p);
        }
    }
    return plan;
}

/// Where the scanner aims: the middle of the block's upper half (as the SL device).
inline Eigen::Vector3d aim_point(const sim::Scene& scene) {
    return scene.T_world_block.translation() + Eigen::Vector3d(0, 0, 0.25 * scene.block_size_m.z());
}

/// A pinhole range camera (OpenCV frame) cast into the scene: points in the sensor frame.
struct PinholeScanConfig {
    int width_px = 400, height_px = 300;
    double focal_px = 680.0;  ///< ~33° x 25° field of view, like the SL rig's cameras.
    double max_range_m = 2.5;
    double noise_sigma_m = 0.0001;
};

inline PointCloud pinhole_scan(const sim::RayCaster& caster, const Pose& T_world_sensor,
                               const PinholeScanConfig& config, std::uint32_t seed) {
    std::mt19937 rng(seed);
    std::normal_distribution<double> noise(0.0, config.noise_sigma_m);
    PointCloud cloud;
    const Eigen::Vector3d origin = T_world_sensor.translation();
    for (int v = 0; v < config.height_px; ++v) {
        for (int u = 0; u < config.width_px; ++u) {
            const Eigen::Vector3d ray =
                Eigen::Vector3d((u - 0.5 * config.width_px) / config.focal_px,
                                (v - 0.5 * config.height_px) / config.focal_px, 1.0)
                    .normalized();
            const auto hit =
                caster.cast(origin, T_world_sensor.linear() * ray, 0.0, config.max_range_m);
            if (!hit) continue;
            cloud.positions.push_back((ray * (hit->distance_m + noise(rng))).cast<float>());
        }
    }
    return cloud;
}

/// The true pose of a scan in the block frame of the first placement, i.e.
/// T_world0_block0 * inverse(T_world_block_now) * T_world_sensor.
inline Pose true_pose_in_first_placement(const Pose& T_world0_block0, const Pose& T_world_block_now,
                                         const Pose& T_world_sensor) {
    return T_world0_block0 * T_world_block_now.inverse() * T_world_sensor;
}

/// The small block as the ray-cast sessions see it: 3 mm mesh, no tent, lying as `placement`.
inline sim::SceneConfig small_block_scene(const sim::BlockPlacement& placement) {
    sim::SceneConfig config = sim::named_scene("small-block").value();
    config.block.grid_step_m = 0.003;
    config.with_tent = false;
    config.placement = placement;
    return config;
}

/// One rendered view of a planned tour.
struct RenderedScan {
    PointCloud cloud;                ///< Sensor frame.
    Pose T_true = Pose::Identity();  ///< Sensor in the first placement's world frame.
    bool turned_over_before = false;
};

/// Renders every view of `plan` (small_block_scene, `first` = the first view's placement)
/// with `pinhole_scan`, seeds 1, 2, ...
inline std::vector<RenderedScan> render_tour(const std::vector<PlannedView>& plan,
                                             const PinholeScanConfig& config = {}) {
    std::map<bool, std::pair<sim::Scene, std::unique_ptr<sim::RayCaster>>> worlds;
    const sim::Scene scene0 = sim::make_scene(small_block_scene(plan.front().placement));
    std::vector<RenderedScan> scans;
    std::uint32_t seed = 1;
    for (const PlannedView& p : plan) {
        const bool turned = p.placement.resting_face == sim::BlockFace::kPosZ;
        if (!worlds.contains(turned)) {
            sim::Scene scene = sim::make_scene(small_block_scene(p.placement));
            auto caster =
                std::make_unique<sim::RayCaster>(sim::RayCaster::create(scene.mesh).value());
            worlds.emplace(turned, std::make_pair(std::move(scene), std::move(caster)));
        }
        const auto& [scene, caster] = worlds.at(turned);
        const Pose T_world_sensor = sim::sensor_looking_at(aim_point(scene), p.view);
        RenderedScan scan;
        scan.cloud = pinhole_scan(*caster, T_world_sensor, config, seed++);
        scan.T_true =
            true_pose_in_first_placement(scene0.T_world_block, scene.T_world_block, T_world_sensor);
        scan.turned_over_before = p.turned_over_before;
        scans.push_back(std::move(scan));
    }
    return scans;
}

/// Rotation (degrees) and translation (metres, at `centroid_scan_m`) error of an estimated
/// pose in the first scan's frame against the truth (both relative to the first scan).
struct PoseError {
    double rotation_deg = 0.0;
    double translation_m = 0.0;
};

inline PoseError pose_error(const Pose& T_first_scan_estimated, const Pose& T_true_first,
                            const Pose& T_true_scan, const Eigen::Vector3d& centroid_scan_m) {
    const Pose T_first_scan_true = T_true_first.inverse() * T_true_scan;
    return {
        .rotation_deg = rotation_angle_deg(T_first_scan_estimated.inverse() * T_first_scan_true),
        .translation_m =
            (T_first_scan_estimated * centroid_scan_m - T_first_scan_true * centroid_scan_m)
                .norm()};
}

/// Centroid of a cloud's finite points (cloud frame).
inline Eigen::Vector3d centroid_of(const PointCloud& cloud) {
    Eigen::Vector3d sum = Eigen::Vector3d::Zero();
    std::size_t n = 0;
    for (std::size_t i = 0; i < cloud.size(); ++i) {
        if (!cloud.positions[i].allFinite()) continue;
        sum += cloud.world_position(i);
        ++n;
    }
    return n == 0 ? sum : Eigen::Vector3d(sum / static_cast<double>(n));
}

}  // namespace anascan::testing
