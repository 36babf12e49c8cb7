// The simulated operator's footprint walk: views that follow the block's outline, as many
// as its length needs, the head at one distance from the nearest part of the stone.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>

#include "anascan/sim/footprint_walk.hpp"
#include "anascan/sim/scanning_tour.hpp"
#include "anascan/sim/sim_structured_light_scanner.hpp"

namespace anascan::sim {
namespace {

/// Distance from a point to the block's box (0 inside).
double distance_to_block(const Eigen::Vector3d& p_world, const BlockPlacement& placement,
                         const Eigen::Vector3d& size_m) {
    const Eigen::Vector3d local = block_pose(placement, size_m).inverse() * p_world;
    const Eigen::Vector3d outside =
        (local.cwiseAbs() - 0.5 * size_m).cwiseMax(Eigen::Vector3d::Zero());
    return outside.norm();
}

TEST(FootprintWalk, ALongerOutlineGetsMoreViewsAndEachStepIsAtMostAFaceOrCornerStep) {
    const WalkSpacing spacing = walk_spacing(1.1, 33.0, 0.5, 30.0);
    // Half of a 33° field at 1.1 m: 2 * 1.1 * tan(16.5°) / 2.
    EXPECT_NEAR(spacing.face_step_m, 1.1 * std::tan(16.5 * M_PI / 180.0), 1e-9);
    const Footprint small = block_footprint({}, {0.45, 0.40, 0.35});
    const Footprint octagon = block_footprint({}, {1.20, 0.60, 0.50});
    const Footprint large = block_footprint({}, {1.50, 0.80, 0.70});
    const int n_small = walk_views(small, spacing), n_octagon = walk_views(octagon, spacing),
              n_large = walk_views(large, spacing);
    // Four corners of three 30° steps each, plus the perimeter in face steps.
    EXPECT_EQ(n_small, static_cast<int>(std::ceil(12.0 + 1.70 / spacing.face_step_m)));
    EXPECT_LT(n_small, n_octagon);
    EXPECT_LT(n_octagon, n_large);
    // Equal fractions are equal steps: consecutive views' aims move by at most one face
    // step, and their outward directions turn by at most one corner step.
    const int n = n_octagon;
    for (int i = 0; i < n; ++i) {
        const OutlinePoint a = outline_point(octagon, spacing, double(i) / n);
        const OutlinePoint b = outline_point(octagon, spacing, double(i + 1) / n);
        EXPECT_LE((b.point_m - a.point_m).norm(), spacing.face_step_m + 1e-9) << i;
        const double turn_deg =
            std::acos(std::clamp(a.outward.dot(b.outward), -1.0, 1.0)) * 180.0 / M_PI;
        EXPECT_LE(turn_deg, spacing.corner_step_deg + 1e-6) << i;
        EXPECT_NEAR(a.outward.norm(), 1.0, 1e-12);
        // The aim lies on the outline.
        const Eigen::Vector2d q = (a.point_m - octagon.centre_m).cwiseAbs();
        const bool on_u =
            std::abs(q.x() - octagon.half_u_m) < 1e-9 && q.y() <= octagon.half_v_m + 1e-9;
        const bool on_v =
            std::abs(q.y() - octagon.half_v_m) < 1e-9 && q.x() <= octagon.half_u_m + 1e-9;
        EXPECT_TRUE(on_u || on_v) << i;
    }
}

TEST(FootprintWalk, AFootprintFollowsTheRestingFaceAndTheYaw) {
    const Footprint on_side =
        block_footprint({.resting_face = BlockFace::kPosY, .yaw_deg = 90.0}, {1.5, 0.8, 0.7});
    // Resting on a y face: 0.8 m is the height, the outline is 1.5 x 0.7 m.
    EXPECT_NEAR(on_side.top_m - on_side.bottom_m, 0.8, 1e-9);
    EXPECT_NEAR(std::max(on_side.half_u_m, on_side.half_v_m), 0.75, 1e-9);
    EXPECT_NEAR(std::min(on_side.half_u_m, on_side.half_v_m), 0.35, 1e-9);
    EXPECT_NEAR(on_side.bottom_m, 0.0, 1e-9);
}

/// The nearest and farthest distance from the head to the stone over a whole tour.
std::pair<double, double> head_to_stone_range(const ScanningTourConfig& tour) {
    auto scene = named_scene("large-block");
    EXPECT_TRUE(scene.has_value());
    auto scanner = SimStructuredLightScanner::open({.scene = *scene});
    double nearest = 1e9, farthest = 0.0;
    for (const TourStep& step : plan_scanning_tour(tour)) {
        EXPECT_TRUE(apply_tour_step(*scanner, tour, step).has_value());
        const Eigen::Vector3d head = scanner->rig().projector.T_world_device.translation();
        const double d = distance_to_block(head, scanner->scene_config().placement,
                                           scanner->scene_config().block.size_m);
        nearest = std::min(nearest, d);
        farthest = std::max(farthest, d);
    }
    return {nearest, farthest};
}

TEST(FootprintWalk, TheHeadKeepsItsDistanceToALargeStoneWhereTheCircleComesTooClose) {
    ScanningTourConfig walk{.views = 0, .flip_after = 0, .follow_footprint = true};
    const int per_side = footprint_views_per_side(walk, named_scene("large-block")->placement,
                                                  named_scene("large-block")->block.size_m, false);
    walk.views = 2 * per_side;
    walk.flip_after = per_side;
    const auto [walk_near, walk_far] = head_to_stone_range(walk);
    // The aim is on the stone 1.1 m away; the nearest part of the stone is at most that far
    // and, seen from 30-50° up, not much nearer.
    EXPECT_GT(walk_near, 0.8);
    EXPECT_LE(walk_far, 1.1 + 1e-6);
    // The circle around the centre of a 1.5 m block passes 0.35 m from its ends.
    const auto [circle_near, circle_far] = head_to_stone_range({.views = 24, .flip_after = 12});
    EXPECT_LT(circle_near, 0.6);
    (void)circle_far;
}

}  // namespace
}  // namespace anascan::sim
