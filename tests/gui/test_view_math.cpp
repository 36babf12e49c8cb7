// The point view's maths: the orbit camera, the level-of-detail split and its controller,
// the colour scales.
#include <gtest/gtest.h>

#include <numeric>

#include "anascan/gui/level_of_detail.hpp"
#include "anascan/gui/orbit_camera.hpp"
#include "anascan/gui/scan_colors.hpp"
#include "anascan/gui/view_overlay.hpp"
#include "anascan/processing/coverage/coverage.hpp"

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

TEST(ViewOverlay, TheScaleBarIsARoundLengthThatFitsAndMeasuresTheView) {
    const ScaleBar bar = scale_bar(0.001, 300.0f);  // 1 mm a pixel, 300 px at most
    EXPECT_DOUBLE_EQ(bar.length_m, 0.2);
    EXPECT_FLOAT_EQ(bar.length_px, 200.0f);
    EXPECT_EQ(bar.label, "20 cm");
    EXPECT_EQ(scale_bar(0.0001, 120.0f).label, "1 cm");
    EXPECT_EQ(scale_bar(0.00002, 300.0f).label, "5 mm");
    EXPECT_EQ(scale_bar(0.01, 250.0f).label, "2 m");
    EXPECT_EQ(scale_bar(0.0, 250.0f).length_px, 0.0f);
    // A camera fitted to a 1 m sphere: the bar's length in pixels is its length in metres
    // on the target's plane, as the projection maps it.
    OrbitCamera camera;
    camera.fit({.centre_m = Eigen::Vector3d(5, 3, 1), .radius_m = 0.5}, 1.0);
    const double m_per_px = metres_per_px_at_target(camera, 800.0f);
    const Eigen::Vector3d right = camera.view().linear().row(0).transpose();  // screen x
    const Eigen::Vector3d a = to_ndc(camera, 1.0, camera.target_m());
    const Eigen::Vector3d b = to_ndc(camera, 1.0, camera.target_m() + 0.1 * right);
    EXPECT_NEAR((b.x() - a.x()) * 0.5 * 800.0, 0.1 / m_per_px, 1e-6);
}

TEST(ViewOverlay, TheAxesTurnWithTheCamera) {
    OrbitCamera camera;
    const auto before = axes_on_screen(camera);
    EXPECT_LT(before[2].y(), -0.5) << "world z is up on the screen (y down)";
    camera.orbit(200.0, 0.0);
    const auto after = axes_on_screen(camera);
    EXPECT_GT((after[0] - before[0]).norm(), 0.1) << "x turns when the camera orbits";
    EXPECT_NEAR(after[2].x(), 0.0, 1e-9) << "z stays vertical when orbiting about it";
}

TEST(ViewOverlay, EachColourModeHasALegendInTheColoursTheViewUses) {
    FieldViewState state;
    for (std::int64_t seq = 1; seq <= 12; ++seq)
        state.scans.push_back({.seq = seq, .state = ScanRowState::kRegistered, .rms_mm = 0.3});
    state.color_mode = ColorMode::kByScan;
    const auto by_scan = color_legend(state, 8);
    ASSERT_EQ(by_scan.size(), 9u) << "the newest 8 and a line for the older";
    EXPECT_EQ(by_scan.back().label, "scan 12");
    EXPECT_TRUE(by_scan.back().color == scan_palette_color(12));
    state.color_mode = ColorMode::kByQuality;
    const auto by_quality = color_legend(state);
    const ScanRow failed{.seq = 13, .state = ScanRowState::kFailed};
    const ScanRow unjoined{.seq = 14, .state = ScanRowState::kUnjoined};
    auto has = [&](Rgb8 c) {
        for (const LegendEntry& e : by_quality)
            if (e.color == c) return true;
        return false;
    };
    EXPECT_TRUE(has(quality_color(state.scans[0])));
    EXPECT_TRUE(has(quality_color(failed)));
    EXPECT_TRUE(has(quality_color(unjoined)));
    state.color_mode = ColorMode::kByCoverage;
    const auto by_coverage = color_legend(state);
    bool ring = false;
    for (const LegendEntry& e : by_coverage)
        ring = ring || (e.ring && e.color == coverage_sample_color(SampleState::kUnobserved));
    EXPECT_TRUE(ring) << "holes in the colour the coverage PLY gives unobserved samples";
}

}  // namespace
}  // namespace anascan::gui
