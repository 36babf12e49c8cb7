// The simulated structured-light scanner end to end: the sim renders a capture of a block
// at 1 m, the real decoder (drivers::sl::decode_stereo: Gray code + phase shift, stereo
// matching, triangulation) turns it into a cloud, and every point is measured against the
// ground-truth mesh (goal: >= 95 % of points within 0.3 mm, RMS near the rig's noise).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <vector>

#include "anascan/drivers/structured_light/stereo_decoder.hpp"
#include "anascan/sim/structured_light_renderer.hpp"
#include "anascan/sim/surface_distance.hpp"
#include "anascan/sim/viewpoints.hpp"
#include "sim_test_scenes.hpp"

namespace anascan::sim {
namespace {

namespace sl = drivers::sl;

// Largest distance measured; points farther from the mesh count as outliers at this value.
constexpr double kMaxDistanceM = 0.01;
// What the rig is built for (docs/simulation.md: PT-M 1024-like, ~0.1 mm at 1 m).
constexpr double kRigNoiseM = 1e-4;

using Accuracy = SurfaceDistanceSummary;

// Distance of each cloud point (cam1 frame) to the mesh, via the rig's true pose.
Accuracy measure(const PointCloud& cloud, const Pose& T_world_cam1, const RayCaster& truth) {
    return summarize_distances(surface_distances(cloud, T_world_cam1, truth, kMaxDistanceM), 3e-4,
                               kMaxDistanceM);
}

class StructuredLightScanTest : public testing::SmallSceneSuite {
protected:
    // The full rig's optics (f = 2700 px, 0.4 m baseline, verging at 1 m) with a crop of
    // the cameras: the same geometry at 1 m as 1600 x 1200, a fraction of the rendering.
    static StructuredLightRig rig_at_1m(const Viewpoint& view) {
        const StructuredLightRigConfig config{.camera_width_px = 320, .camera_height_px = 240};
        const Eigen::Vector3d target = scene_->T_world_block.translation() +
                                       Eigen::Vector3d(0, 0, 0.25 * scene_->block_size_m.z());
        return make_structured_light_rig(config, sensor_looking_at(target, view));
    }
    struct Scan {
        StructuredLightCapture capture;
        sl::StereoDecodeResult result;
    };
    static Scan scan(const StructuredLightRig& rig,
                     const StructuredLightRenderConfig& render = {}) {
        Scan s{
            .capture =
                render_structured_light(*caster_, triangle_albedos(*scene_), rig, render).value()};
        const sl::StereoDecodeConfig decode{.sequence = decoder_sequence(render.patterns)};
        auto result =
            sl::decode_stereo(s.capture.cam1, s.capture.cam2, stereo_calibration(rig), decode);
        EXPECT_TRUE(result) << result.error().message;
        if (result) s.result = *std::move(result);
        return s;
    }
};

// cam1 pixels whose surface point the projector lights and cam2 sees (from the renderer's
// truth): what a perfect decoder could turn into points.
std::size_t seen_by_both(const StructuredLightCapture& c) {
    const PinholeModel &cam1 = c.rig.cam1, &cam2 = c.rig.cam2;
    std::size_t n = 0;
    for (int y = 0; y < cam1.height_px; ++y) {
        for (int x = 0; x < cam1.width_px; ++x) {
            const float z = c.truth1.depth_m.at<float>(y, x);
            if (std::isnan(c.truth1.projector_xy.at<cv::Vec2f>(y, x)[0])) continue;
            const Eigen::Vector3d local((x - cam1.cx_px) / cam1.fx_px * z,
                                        (y - cam1.cy_px) / cam1.fy_px * z, z);
            const Eigen::Vector3d q = cam2.project(cam1.T_world_device * local);
            const int u = int(std::lround(q.x())), v = int(std::lround(q.y()));
            if (u < 0 || v < 0 || u >= cam2.width_px || v >= cam2.height_px) continue;
            if (std::abs(c.truth2.depth_m.at<float>(v, u) - q.z()) < 2e-3) ++n;
        }
    }
    return n;
}

void print(const char* what, const sl::StereoDecodeResult& r, const Accuracy& a) {
    std::printf(
        "%s: %zu points of %zu cam1 pixels (cam1 valid %zu, matched %zu, ray gap %zu), "
        "%.2f %% within 0.3 mm, median %.3f mm, RMS %.3f mm, RMS of best 95 %% %.3f mm, "
        "median ray gap %.3f mm\n",
        what, a.points, r.pixel_count, r.cam1_valid, r.matched, r.rejected_ray_gap,
        100.0 * a.within_fraction, 1e3 * a.median_m, 1e3 * a.rms_m, 1e3 * a.rms_best95_m,
        1e3 * r.median_ray_gap_m);
}

// The renderer projects the decoder's images; the sim's own description of each pattern
// (kind, axis, level) must say the same, image for image.
TEST(PatternSequence, SimPatternsAreTheDecodersPatterns) {
    const PatternSequenceConfig config;
    const std::vector<Pattern> sim = pattern_sequence(config);
    const std::vector<cv::Mat> decoder = sl::make_patterns(decoder_sequence(config));
    ASSERT_EQ(sim.size(), decoder.size());
    for (std::size_t i = 0; i < sim.size(); ++i) {
        // Phase levels: the sim's exact cosine, the decoder's rounded to 8 bits.
        const double tolerance = sim[i].kind == PatternKind::kPhase ? 1.0 : 0.0;
        EXPECT_LE(cv::norm(projector_image(config, sim[i]), decoder[i], cv::NORM_INF), tolerance)
            << "pattern " << i;
    }
}

TEST(RayCasterClosestPoint, IsTheExactDistanceToATriangle) {
    Mesh mesh;
    mesh.vertices.positions = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}};
    mesh.triangles = {{0, 1, 2}};
    const RayCaster caster = RayCaster::create(mesh).value();
    const auto inside = caster.closest_point({0.25, 0.25, 0.003}, 0.01);
    ASSERT_TRUE(inside);
    EXPECT_NEAR(inside->distance_m, 0.003, 1e-12);
    const auto edge = caster.closest_point({0.5, -0.004, 0.003}, 0.01);  // Nearest: an edge.
    ASSERT_TRUE(edge);
    EXPECT_NEAR(edge->distance_m, 0.005, 1e-12);
    EXPECT_FALSE(caster.closest_point({0.25, 0.25, 0.02}, 0.01));
}

TEST_F(StructuredLightScanTest, BlockAt1mIsWithin0_3mmOfTheTrueSurface) {
    const StructuredLightRig rig = rig_at_1m({.azimuth_deg = 30, .elevation_deg = 40});
    const auto [capture, result] = scan(rig);
    const Accuracy a = measure(result.cloud, rig.cam1.T_world_device, *caster_);
    print("block at 1 m, Gray code + 4-step phase (period 8 px)", result, a);
    const std::size_t both = seen_by_both(capture);
    std::printf("cam1 pixels lit and seen by cam2: %zu; points: %.1f %% of them\n", both,
                100.0 * double(a.points) / double(both));
    EXPECT_GT(double(a.points), 0.9 * double(both));
    EXPECT_GE(a.within_fraction, 0.95);
    // Every point, outliers included (a point farther than 10 mm counts as 10 mm).
    EXPECT_LT(a.rms_m, kRigNoiseM);
}

// The error follows the image noise: four times the sensor noise (read noise 4 DN, shot
// noise variance x16) gives clearly larger errors, noise-free images smaller ones.
TEST_F(StructuredLightScanTest, ErrorFollowsTheImageNoise) {
    const StructuredLightRig rig = rig_at_1m({.azimuth_deg = -20, .elevation_deg = 35});
    StructuredLightRenderConfig noisy, quiet;
    noisy.read_noise_dn = 4.0 * quiet.read_noise_dn;
    noisy.shot_noise_dn2_per_dn = 16.0 * quiet.shot_noise_dn2_per_dn;
    quiet.read_noise_dn = 0.0;
    quiet.shot_noise_dn2_per_dn = 0.0;
    const auto at_noise = [&](const StructuredLightRenderConfig& render, const char* what) {
        const sl::StereoDecodeResult r = scan(rig, render).result;
        const Accuracy a = measure(r.cloud, rig.cam1.T_world_device, *caster_);
        print(what, r, a);
        return a;
    };
    const Accuracy none = at_noise(quiet, "noise-free images");
    const Accuracy base = at_noise({}, "default noise (1 DN read, 0.02 DN^2/DN shot)");
    const Accuracy x4 = at_noise(noisy, "4x the sensor noise");
    EXPECT_LT(none.rms_best95_m, base.rms_best95_m);
    EXPECT_GT(x4.rms_best95_m, 2.0 * base.rms_best95_m);
    EXPECT_GE(base.within_fraction, 0.95);
}

}  // namespace
}  // namespace anascan::sim
