#pragma once
/// \file
/// The simulated operator's walk along the block's footprint: the head keeps its distance
/// to the nearest part of the stone, not to its centre, so that a long block is seen as
/// closely as a small one and its long faces get as many views as their length needs.

#include <Eigen/Core>

#include "anascan/sim/scene.hpp"

namespace anascan::sim {

/// The block seen from above, in the world frame of one placement: a rectangle (the block
/// rests on a face) and the heights of its bottom and top.
struct Footprint {
    Eigen::Vector2d centre_m = Eigen::Vector2d::Zero();
    Eigen::Vector2d axis_u = Eigen::Vector2d::UnitX();  ///< Unit; axis_v is it turned by +90°.
    double half_u_m = 0.0;
    double half_v_m = 0.0;
    double bottom_m = 0.0;
    double top_m = 0.0;
};

Footprint block_footprint(const BlockPlacement& placement, const Eigen::Vector3d& size_m);

/// How finely the walk samples the outline: along a face the aim moves by at most
/// `face_step_m` between views; at a corner the view turns by at most `corner_step_deg`.
struct WalkSpacing {
    double face_step_m = 0.33;
    double corner_step_deg = 30.0;
};

/// The spacing of a head `distance_m` from the stone with a horizontal field of
/// `field_width_deg`, consecutive views overlapping by `overlap` (0-1) of the field.
WalkSpacing walk_spacing(double distance_m, double field_width_deg, double overlap,
                         double corner_step_deg);

/// Views needed for one side: the outline's length in face steps plus its four corners in
/// corner steps, rounded up.
int walk_views(const Footprint& footprint, const WalkSpacing& spacing);

/// A point of the outline and the horizontal direction away from the block there.
struct OutlinePoint {
    Eigen::Vector2d point_m = Eigen::Vector2d::Zero();
    Eigen::Vector2d outward = Eigen::Vector2d::UnitX();
};

/// The point at `fraction` (wrapped into [0, 1)) of the walk, counter-clockwise from the
/// middle of the +u face, fractions measured in steps (a corner counts as its corner steps,
/// a face as its face steps), so that equal fractions are equal steps of the walk.
OutlinePoint outline_point(const Footprint& footprint, const WalkSpacing& spacing, double fraction);

}  // namespace anascan::sim
