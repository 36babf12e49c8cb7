#include "anascan/sim/scanning_tour.hpp"

#include <algorithm>
#include <cmath>
#include <random>

#include "anascan/sim/footprint_walk.hpp"
#include "anascan/sim/sim_structured_light_scanner.hpp"
#include "anascan/sim/sim_tof_scanner.hpp"

namespace anascan::sim {
namespace {

BlockFace opposite(BlockFace face) {
    switch (face) {
        case BlockFace::kPosX:
            return BlockFace::kNegX;
        case BlockFace::kNegX:
            return BlockFace::kPosX;
        case BlockFace::kPosY:
            return BlockFace::kNegY;
        case BlockFace::kNegY:
            return BlockFace::kPosY;
        case BlockFace::kPosZ:
            return BlockFace::kNegZ;
        case BlockFace::kNegZ:
            return BlockFace::kPosZ;
    }
    return BlockFace::kPosZ;
}

/// Views of one side of the block: `count` azimuths evenly around, elevations alternating.
void add_side(const ScanningTourConfig& config, int count, bool turned, std::mt19937_64& rng,
              std::vector<TourStep>& steps) {
    std::uniform_real_distribution<double> jitter(-config.jitter_deg, config.jitter_deg);
    const double step_deg = 360.0 / std::max(count, 1);
    for (int i = 0; i < count; ++i) {
        TourStep step;
        step.index = static_cast<int>(steps.size());
        step.turned = turned;
        step.turn_now = turned && i == 0;
        step.view.distance_m = config.distance_m;
        step.view.azimuth_deg = config.start_azimuth_deg + i * step_deg + jitter(rng);
        if (config.follow_footprint)
            step.walk_fraction = (i + 0.5) / std::max(count, 1) + jitter(rng) / 360.0;
        step.view.elevation_deg =
            (i % 2 == 0 ? config.elevation_low_deg : config.elevation_high_deg) + jitter(rng);
        steps.push_back(step);
    }
}

}  // namespace

int footprint_views_per_side(const ScanningTourConfig& config, const BlockPlacement& placement,
                             const Eigen::Vector3d& size_m, bool terrestrial) {
    if (terrestrial) return std::max(1, config.terrestrial_views_per_side);
    return walk_views(block_footprint(placement, size_m),
                      walk_spacing(config.distance_m, config.field_width_deg, config.field_overlap,
                                   config.corner_step_deg));
}

std::vector<TourStep> plan_scanning_tour(const ScanningTourConfig& config) {
    std::vector<TourStep> steps;
    std::mt19937_64 rng(config.seed);
    const int views = std::max(config.views, 0);
    const int first_side = config.flip_after > 0 ? std::min(config.flip_after, views) : views;
    add_side(config, first_side, false, rng, steps);
    add_side(config, views - first_side, true, rng, steps);
    return steps;
}

BlockPlacement tour_placement(const ScanningTourConfig& config, const BlockPlacement& first,
                              const TourStep& step) {
    if (!step.turned) return first;
    BlockPlacement turned = first;
    turned.resting_face = opposite(first.resting_face);
    turned.yaw_deg += config.turned_yaw_deg;
    turned.position_m += config.turned_offset_m;
    return turned;
}

namespace {

struct PlacedStep {
    SimScanner* sim = nullptr;
    Pose T_truth_world = Pose::Identity();  ///< Device world of the step -> first placement.
    Eigen::Vector3d block_centre_m = Eigen::Vector3d::Zero();  ///< Device world.
};

// Lays the block as the step says (the first placement is the named scene's; the
// scanner's scene holds the current one).
PlacedStep place_for_step(drivers::Scanner& scanner, const ScanningTourConfig& config,
                          const TourStep& step) {
    auto* sim = dynamic_cast<SimScanner*>(&scanner);
    if (sim == nullptr) return {};
    auto first = named_scene(sim->scene_config().name);
    const BlockPlacement start = first ? first->placement : sim->scene_config().placement;
    const BlockPlacement now = tour_placement(config, start, step);
    const Eigen::Vector3d size = sim->scene_config().block.size_m;
    const bool moved = now.resting_face != sim->scene_config().placement.resting_face ||
                       now.yaw_deg != sim->scene_config().placement.yaw_deg ||
                       now.position_m != sim->scene_config().placement.position_m;
    if (moved) sim->place_block(now);
    return {sim, block_pose(start, size) * block_pose(now, size).inverse(),
            block_pose(now, size).translation()};
}

constexpr double kRadToDeg = 180.0 / 3.14159265358979323846;

/// The footprint walk's view: the head aims at the outline point at three quarters of the
/// block's height from outside; a terrestrial station stands out from the block there.
void walk_to(SimScanner& sim, const ScanningTourConfig& config, const TourStep& step) {
    const Footprint footprint =
        block_footprint(sim.scene_config().placement, sim.scene_config().block.size_m);
    const WalkSpacing spacing = walk_spacing(config.distance_m, config.field_width_deg,
                                             config.field_overlap, config.corner_step_deg);
    const OutlinePoint at = outline_point(footprint, spacing, *step.walk_fraction);
    const double azimuth_deg = std::atan2(at.outward.y(), at.outward.x()) * kRadToDeg;
    if (auto* sl = dynamic_cast<SimStructuredLightScanner*>(&sim)) {
        const double aim_z = footprint.bottom_m + 0.75 * (footprint.top_m - footprint.bottom_m);
        sl->aim_at(Eigen::Vector3d(at.point_m.x(), at.point_m.y(), aim_z));
        sl->move_to({.azimuth_deg = azimuth_deg,
                     .elevation_deg = step.view.elevation_deg,
                     .distance_m = step.view.distance_m});
    }
    if (auto* tof = dynamic_cast<SimTofScanner*>(&sim))
        tof->move_to({.azimuth_deg = azimuth_deg,
                      .distance_m = config.tripod_distance_m,
                      .height_m = config.tripod_height_m});
}

}  // namespace

std::optional<Pose> apply_tour_step(drivers::Scanner& scanner, const ScanningTourConfig& config,
                                    const TourStep& step) {
    const PlacedStep placed = place_for_step(scanner, config, step);
    if (placed.sim == nullptr) return std::nullopt;
    if (step.walk_fraction) {
        walk_to(*placed.sim, config, step);
        return placed.T_truth_world;
    }
    if (auto* sl = dynamic_cast<SimStructuredLightScanner*>(placed.sim)) {
        sl->aim_at(std::nullopt);
        sl->move_to(step.view);
    }
    if (auto* tof = dynamic_cast<SimTofScanner*>(placed.sim))
        tof->move_to({.azimuth_deg = step.view.azimuth_deg,
                      .distance_m = config.tripod_distance_m,
                      .height_m = config.tripod_height_m});
    return placed.T_truth_world;
}

std::optional<Pose> apply_guided_view(drivers::Scanner& scanner, const ScanningTourConfig& config,
                                      const GuidedView& view) {
    TourStep step;
    step.turned = view.turned;
    const PlacedStep placed = place_for_step(scanner, config, step);
    if (placed.sim == nullptr) return std::nullopt;
    const Pose T_world_truth = placed.T_truth_world.inverse();
    const Eigen::Vector3d sensor = T_world_truth * view.sensor_m, aim = T_world_truth * view.aim_m;
    const Eigen::Vector3d offset = sensor - aim;
    if (auto* sl = dynamic_cast<SimStructuredLightScanner*>(placed.sim)) {
        sl->aim_at(aim);
        sl->move_to({.azimuth_deg = std::atan2(offset.y(), offset.x()) * kRadToDeg,
                     .elevation_deg = std::asin(offset.z() / offset.norm()) * kRadToDeg,
                     .distance_m = offset.norm()});
    }
    if (auto* tof = dynamic_cast<SimTofScanner*>(placed.sim)) {
        const Eigen::Vector3d around = sensor - placed.block_centre_m;
        tof->move_to({.azimuth_deg = std::atan2(around.y(), around.x()) * kRadToDeg,
                      .distance_m = around.head<2>().norm(),
                      .height_m = sensor.z()});
    }
    return placed.T_truth_world;
}

}  // namespace anascan::sim
