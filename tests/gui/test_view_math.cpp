// The point view's maths: the orbit camera, the level-of-detail split and its controller,
// the colour scales.
#include <gtest/gtest.h>

#include <numeric>

#include "anascan/gui/level_of_detail.hpp"
#include "anascan/gui/orbit_camera.hpp"
#include "anascan/gui/scan_colors.hpp"

namespace anascan::gui {
namespace {

/// Normalised device coordinates of a world point.
Eigen::Vector3d to_ndc(const OrbitCamera& camera, double aspect, const Eigen::Vector3d& p) {
    const Eigen::Vector4d clip =
        camera.projection(aspect) * camera.view().matrix() * p.homogeneous();
    return clip.head<3>() / clip.w();
}

TEST(OrbitCamera, FitShowsTheWholeStoneCentredEvenFarFromTheOrigin) {
    // Site coordinates of a terrestrial scanner: hundreds of kilometres from the origin.
    const BoundingSphere stone{.centre_m = {512'345.25, 4'123'456.5, 87.0}, .radius_m = 0.6};
    for (double aspect : {0.5, 1.0, 1.6}) {
        OrbitCamera camera;
        camera.orbit(37.0, -12.0);
        camera.fit(stone, aspect);
        EXPECT_NEAR(to_ndc(camera, aspect, stone.centre_m).head<2>().norm(), 0.0, 1e-6);
        for (int i = 0; i < 6; ++i) {  // the sphere's extreme points on every axis
            Eigen::Vector3d offset = Eigen::Vector3d::Zero();
            offset[i / 2] = (i % 2 == 0 ? 1.0 : -1.0) * stone.radius_m;
            const Eigen::Vector3d ndc = to_ndc(camera, aspect, stone.centre_m + offset);
            EXPECT_LE(ndc.head<2>().cwiseAbs().maxCoeff(), 1.0) << "aspect " << aspect;
            EXPECT_GT(ndc.z(), -1.0);
            EXPECT_LT(ndc.z(), 1.0);
        }
    }
}

TEST(OrbitCamera, OrbitKeepsTheDistancePanMovesInTheViewPlaneZoomApproaches) {
    OrbitCamera camera;
    camera.fit({.centre_m = {1.0, 2.0, 3.0}, .radius_m = 0.5});
    const double d0 = camera.distance_m();
    const Eigen::Vector3d forward0 = (camera.target_m() - camera.eye_m()).normalized();
    camera.orbit(120.0, 45.0);
    EXPECT_NEAR((camera.eye_m() - camera.target_m()).norm(), d0, 1e-9);
    const Eigen::Vector3d forward = (camera.target_m() - camera.eye_m()).normalized();
    EXPECT_LT(forward.dot(forward0), 0.999);  // the direction did change

    const Eigen::Vector3d target_before = camera.target_m();
    camera.pan(40.0, -25.0, 800.0);
    const Eigen::Vector3d moved = camera.target_m() - target_before;
    EXPECT_GT(moved.norm(), 0.0);
    EXPECT_NEAR(moved.dot(forward), 0.0, 1e-9);  // no motion along the view direction

    camera.zoom(2.0);
    EXPECT_LT(camera.distance_m(), d0);
    camera.zoom(1000.0);
    EXPECT_GT(camera.distance_m(), 0.0);  // never through the target
    const Eigen::Isometry3d view = camera.view();
    EXPECT_NEAR((view.linear() * view.linear().transpose() - Eigen::Matrix3d::Identity()).norm(),
                0.0, 1e-12);
    EXPECT_NEAR((view * camera.eye_m()).norm(), 0.0, 1e-9);
}

TEST(LevelOfDetail, EveryChunkKeepsTheSameFractionWithinTheBudget) {
    const std::vector<std::size_t> sizes{1'000'000, 250'000, 0, 3, 4'000'000};
    const std::size_t total = std::accumulate(sizes.begin(), sizes.end(), std::size_t{0});
    EXPECT_EQ(points_to_draw(sizes, total), sizes);  // within budget: everything

    const std::size_t budget = 1'000'000;
    const std::vector<std::size_t> drawn = points_to_draw(sizes, budget);
    ASSERT_EQ(drawn.size(), sizes.size());
    EXPECT_LE(std::accumulate(drawn.begin(), drawn.end(), std::size_t{0}), budget + sizes.size());
    EXPECT_EQ(drawn[2], 0u);
    EXPECT_EQ(drawn[3], 1u);  // a tiny chunk never vanishes
    const double f0 = static_cast<double>(drawn[0]) / static_cast<double>(sizes[0]);
    const double f4 = static_cast<double>(drawn[4]) / static_cast<double>(sizes[4]);
    EXPECT_NEAR(f0, f4, 1e-5);
    EXPECT_NEAR(f0, static_cast<double>(budget) / static_cast<double>(total), 1e-5);
}

TEST(LevelOfDetail, ControllerShrinksOnSlowFramesAndGrowsBackOnFastOnes) {
    LodController lod({.target_frame_ms = 25.0,
                       .min_budget_points = 100'000,
                       .initial_budget_points = 10'000'000});
    const std::size_t total = 10'000'000;
    EXPECT_EQ(lod.update(50.0, total), 5'000'000u);   // twice too slow: half
    EXPECT_EQ(lod.update(500.0, total), 2'500'000u);  // at most halved per frame
    EXPECT_EQ(lod.update(20.0, total), 2'500'000u);   // near the target: unchanged
    EXPECT_EQ(lod.update(10.0, total), 3'000'000u);   // clearly fast: +20 %
    for (int i = 0; i < 50; ++i) lod.update(1000.0, total);
    EXPECT_EQ(lod.budget(), 100'000u);  // never below the minimum
    for (int i = 0; i < 100; ++i) lod.update(1.0, total);
    EXPECT_EQ(lod.budget(), total);  // never above what exists
}

TEST(LevelOfDetail, ThinnedPointsGrowToFillTheGaps) {
    EXPECT_FLOAT_EQ(thinned_point_size_px(2.0f, 1.0), 2.0f);
    EXPECT_FLOAT_EQ(thinned_point_size_px(2.0f, 0.64), 2.5f);
    EXPECT_FLOAT_EQ(thinned_point_size_px(2.0f, 1e-6), 4.0f);  // capped at 2x
}

TEST(ScanColors, PaletteTellsNeighboursApartQualityFollowsTheRms) {
    for (std::int64_t seq = 1; seq < 40; ++seq) {
        const Rgb8 a = scan_palette_color(seq), b = scan_palette_color(seq + 1);
        const int diff = std::abs(a.r - b.r) + std::abs(a.g - b.g) + std::abs(a.b - b.b);
        EXPECT_GT(diff, 60) << "scans " << seq << " and " << seq + 1;
    }
    ScanRow row{.seq = 1, .state = ScanRowState::kRegistered, .rms_mm = 0.2};
    const Rgb8 good = quality_color(row);
    row.rms_mm = 3.0;
    const Rgb8 poor = quality_color(row);
    row.state = ScanRowState::kFailed;
    const Rgb8 failed = quality_color(row);
    EXPECT_GT(good.g, good.r);
    EXPECT_GT(poor.r, poor.g);
    EXPECT_GT(failed.r, 200);
    EXPECT_LT(failed.g, 80);
}

}  // namespace
}  // namespace anascan::gui
