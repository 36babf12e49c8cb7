#pragma once
/// \file
/// The simulated operator of a capture session: where the scanner stands for each view
/// around the block, and when the stone is turned over. Applied to a simulated scanner
/// before each capture; a real scanner is moved by hand and ignores it.

#include <cstdint>
#include <optional>
#include <vector>

#include "anascan/drivers/scanner.hpp"
#include "anascan/processing/core/pose.hpp"
#include "anascan/sim/scene.hpp"
#include "anascan/sim/viewpoints.hpp"

namespace anascan::sim {

/// A walk around the block with alternating elevation and a little jitter (a person, not a
/// turntable): either on a circle around the block's centre, the views of each side spread
/// evenly in azimuth, or along its footprint (`follow_footprint`), the head at a fixed
/// distance from the nearest part of the stone and the views spread evenly in walk steps
/// (footprint_walk.hpp).
struct ScanningTourConfig {
    int views = 24;       ///< Captures in the whole tour.
    int flip_after = 12;  ///< Turned over after this many views; 0: never.
    /// Circle: structured-light head to the middle of the block's upper half. Footprint
    /// walk: head to the aim, on the outline at three quarters of the block's height.
    double distance_m = 1.1;
    bool follow_footprint = false;
    /// Footprint walk: the head's horizontal field (the simulated head: 640 px at f 1080 px,
    /// 33°), the share of it consecutive views along a face have in common, and the largest
    /// turn between views at a corner.
    double field_width_deg = 33.0;
    double field_overlap = 0.5;
    double corner_step_deg = 30.0;
    int terrestrial_views_per_side = 4;  ///< sim:tof stations per side (a panorama each).
    double elevation_low_deg = 30.0;     ///< Even views.
    double elevation_high_deg = 50.0;    ///< Odd views.
    double start_azimuth_deg = 15.0;
    double jitter_deg = 3.0;  ///< Uniform ± on azimuth and elevation.
    /// Terrestrial scanner stations (sim:tof): tripod distance and height.
    double tripod_distance_m = 3.0;
    double tripod_height_m = 1.5;
    /// Once turned over the block rests on the face opposite its first resting face,
    /// turned about the vertical by this much more and moved by this much (people do not
    /// put a stone back exactly where it lay).
    double turned_yaw_deg = 20.0;
    Eigen::Vector2d turned_offset_m{0.03, -0.02};
    std::uint64_t seed = 1;
};

/// One view of the tour.
struct TourStep {
    int index = 0;          ///< 0-based.
    Viewpoint view;         ///< Structured-light head around the target (world azimuth).
    bool turned = false;    ///< The block lies turned over for this view.
    bool turn_now = false;  ///< First view after turning over: the operator marks it.
    /// Footprint walk: where along the walk the view stands (0-1, footprint_walk.hpp);
    /// `view` then holds the elevation and the distance.
    std::optional<double> walk_fraction;
};

/// Views per side of the footprint walk around a block of `size_m` lying as `placement`:
/// along its outline in face and corner steps (structured light), or
/// `terrestrial_views_per_side` stations (a terrestrial scanner sees a whole side at once).
int footprint_views_per_side(const ScanningTourConfig& config, const BlockPlacement& placement,
                             const Eigen::Vector3d& size_m, bool terrestrial);

/// The views of a tour; deterministic for a config.
std::vector<TourStep> plan_scanning_tour(const ScanningTourConfig& config);

/// Where the block lies for a step, given the scene's first placement.
BlockPlacement tour_placement(const ScanningTourConfig& config, const BlockPlacement& first,
                              const TourStep& step);

/// Moves a simulated scanner (sim:structured-light or sim:tof) to the step's view and lays
/// the block as the step says. Returns the transform from the simulator's world frame of
/// that step to the world frame of the first placement (so that true poses of all views
/// are in one frame that moves with the stone), or nothing for a device that is not
/// simulated (a real scanner is moved by the operator).
std::optional<Pose> apply_tour_step(drivers::Scanner& scanner, const ScanningTourConfig& config,
                                    const TourStep& step);

/// A view chosen by the next-best-view, in the frame of the block's first placement (the
/// session's truth frame, which moves with the stone).
struct GuidedView {
    Eigen::Vector3d sensor_m = Eigen::Vector3d::Zero();  ///< Sensor position.
    Eigen::Vector3d aim_m = Eigen::Vector3d::Zero();     ///< Point aimed at.
    bool turned = false;                                 ///< The block lies turned over.
};

/// As apply_tour_step, for a guided view: the structured-light head stands at the sensor
/// position aiming at the aim point; a terrestrial station stands on its tripod at the
/// sensor's azimuth and distance around the block.
std::optional<Pose> apply_guided_view(drivers::Scanner& scanner, const ScanningTourConfig& config,
                                      const GuidedView& view);

}  // namespace anascan::sim
