// Pattern images of the simulated structured-light scanner: Gray code and phase shift as
// OpenCV's structured_light module makes them, shadows, seeds, the calibration file.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <numbers>
#include <opencv2/core.hpp>
#include <opencv2/structured_light.hpp>
#include <optional>

#include "anascan/sim/structured_light_renderer.hpp"
#include "anascan/sim/viewpoints.hpp"
#include "sim_test_scenes.hpp"
#include "structured_light_test_support.hpp"

namespace anascan::sim {
namespace {

using sl_test::decode_gray;
using sl_test::facing_projector;
using sl_test::lit_projector_xy;
using sl_test::narrow_rig;
using sl_test::StructuredLightTest;

TEST(PatternSequence, GrayCodeImagesAreOpenCvsGrayCodePattern) {
    const PatternSequenceConfig config;
    const std::vector<Pattern> sequence = pattern_sequence(config);
    auto opencv = cv::structured_light::GrayCodePattern::create([] {
        cv::structured_light::GrayCodePattern::Params params;
        params.width = 1280;
        params.height = 800;
        return params;
    }());
    std::vector<cv::Mat> expected;
    ASSERT_TRUE(opencv->generate(expected));
    cv::Mat white, black;
    opencv->getImagesForShadowMasks(black, white);
    expected.push_back(white);
    expected.push_back(black);
    ASSERT_EQ(expected.size(), 44u);
    ASSERT_EQ(sequence.size(), 44u + 8u);  // + 4 column and 4 row phase shifts.
    for (std::size_t i = 0; i < expected.size(); ++i)
        EXPECT_EQ(cv::norm(projector_image(config, sequence[i]), expected[i], cv::NORM_INF), 0.0)
            << "pattern " << i;
    EXPECT_EQ(sequence[44].kind, PatternKind::kPhase);
}

TEST_F(StructuredLightTest, GrayCodeDecodesToTheProjectorPixelTheRayGeometryGives) {
    const StructuredLightRig r = rig(narrow_rig(), {.azimuth_deg = 30, .elevation_deg = 50});
    const StructuredLightCapture capture = render(r);
    for (int c = 0; c < 2; ++c) {
        const PinholeModel& cam = c == 0 ? r.cam1 : r.cam2;
        const std::vector<cv::Mat>& images = c == 0 ? capture.cam1 : capture.cam2;
        int lit = 0, valid = 0, exact = 0, near = 0;
        for (int y = 0; y < cam.height_px; ++y) {
            for (int x = 0; x < cam.width_px; ++x) {
                const auto xy = lit_projector_xy(*caster_, r, cam, x, y);
                if (!xy) continue;
                ++lit;
                if (images[42].at<std::uint8_t>(y, x) - images[43].at<std::uint8_t>(y, x) < 20)
                    continue;
                ++valid;
                const int col = decode_gray(images, 0, 11, x, y),
                          row = decode_gray(images, 22, 10, x, y);
                const int dc = col - static_cast<int>(std::lround(xy->x()));
                const int dr = row - static_cast<int>(std::lround(xy->y()));
                exact += (dc == 0 && dr == 0) ? 1 : 0;
                near += (std::abs(dc) <= 1 && std::abs(dr) <= 1) ? 1 : 0;
            }
        }
        std::printf(
            "camera %d: %d lit pixels, %.2f %% decodable, %.2f %% exact, %.2f %% within 1 px\n",
            c + 1, lit, 100.0 * valid / lit, 100.0 * exact / valid, 100.0 * near / valid);
        ASSERT_GT(lit, cam.width_px * cam.height_px / 2) << "camera " << c + 1;
        EXPECT_GT(valid, 0.98 * lit) << "camera " << c + 1;
        EXPECT_GT(exact, 0.85 * valid) << "camera " << c + 1;
        EXPECT_GT(near, 0.995 * valid) << "camera " << c + 1;
    }
}

TEST_F(StructuredLightTest, PhaseShiftGivesSubPixelProjectorColumns) {
    const StructuredLightRig r = rig(narrow_rig(), {.azimuth_deg = -20, .elevation_deg = 45});
    const StructuredLightRenderConfig config;
    const StructuredLightCapture capture = render(r, config);
    const double period = config.patterns.phase_period_px;
    double sum2 = 0.0;
    int n = 0;
    for (int y = 0; y < r.cam1.height_px; ++y) {
        for (int x = 0; x < r.cam1.width_px; ++x) {
            const auto xy = lit_projector_xy(*caster_, r, r.cam1, x, y);
            if (!xy) continue;
            double s = 0.0, co = 0.0;
            for (int k = 0; k < config.patterns.phase_steps; ++k) {
                const double v = capture.cam1[44 + k].at<std::uint8_t>(y, x);
                s += v * std::sin(2.0 * std::numbers::pi * k / config.patterns.phase_steps);
                co += v * std::cos(2.0 * std::numbers::pi * k / config.patterns.phase_steps);
            }
            const double expected = 2.0 * std::numbers::pi * xy->x() / period;
            const double e = std::remainder(std::atan2(s, co) - expected, 2.0 * std::numbers::pi);
            sum2 += e * e;
            ++n;
        }
    }
    ASSERT_GT(n, 10000);
    const double rms_px = std::sqrt(sum2 / n) * period / (2.0 * std::numbers::pi);
    std::printf("phase error RMS %.4f projector px over %d pixels\n", rms_px, n);
    EXPECT_LT(rms_px, 0.07);
}

TEST_F(StructuredLightTest, ProjectorShadowsStayDarkAndLitSurfacesBright) {
    // A wide view so that the block's projector shadow on the ground is in the images.
    StructuredLightRigConfig wide = narrow_rig();
    wide.camera_focal_px = 300.0;
    const StructuredLightRig r =
        rig(wide, {.azimuth_deg = 0, .elevation_deg = 30, .distance_m = 1.2});
    const StructuredLightCapture capture = render(r);
    int shadowed = 0, dark = 0, lit = 0, bright = 0;
    for (int y = 2; y < r.cam1.height_px - 2; ++y) {
        for (int x = 2; x < r.cam1.width_px - 2; ++x) {
            const Eigen::Vector3d o = r.cam1.T_world_device.translation(),
                                  d = r.cam1.ray_world(x, y);
            const auto hit = caster_->cast(o, d);
            if (!hit) continue;
            const int contrast =
                capture.cam1[42].at<std::uint8_t>(y, x) - capture.cam1[43].at<std::uint8_t>(y, x);
            if (!lit_projector_xy(*caster_, r, r.cam1, x, y)) {
                ++shadowed;
                dark += contrast < 4 ? 1 : 0;
            } else if (scene_->triangle_kinds[hit->triangle] == SurfaceKind::kStone &&
                       facing_projector(r, o + hit->distance_m * d, hit->normal) > 0.3) {
                ++lit;
                bright += contrast > 8 ? 1 : 0;
            }
        }
    }
    std::printf("shadowed %d (dark %d), lit stone %d (bright %d)\n", shadowed, dark, lit, bright);
    ASSERT_GT(shadowed, 200);
    ASSERT_GT(lit, 200);
    EXPECT_GT(dark, 0.9 * shadowed);
    EXPECT_GT(bright, 0.95 * lit);
}

TEST_F(StructuredLightTest, SameSeedSameImagesAndBadProjectorSizeIsAnError) {
    StructuredLightRigConfig tiny = narrow_rig();
    tiny.camera_width_px = 40;
    tiny.camera_height_px = 30;
    const StructuredLightRig r = rig(tiny, {});
    const StructuredLightCapture a = render(r), b = render(r);
    StructuredLightRenderConfig other;
    other.seed = 2;
    const StructuredLightCapture c = render(r, other);
    double diff_same = 0.0, diff_other = 0.0;
    for (std::size_t i = 0; i < a.cam1.size(); ++i) {
        diff_same += cv::norm(a.cam1[i], b.cam1[i], cv::NORM_L1) +
                     cv::norm(a.cam2[i], b.cam2[i], cv::NORM_L1);
        diff_other += cv::norm(a.cam1[i], c.cam1[i], cv::NORM_L1);
    }
    EXPECT_EQ(diff_same, 0.0);
    EXPECT_GT(diff_other, 0.0);
    // The capture carries its true poses; writing it into an impossible folder is an error.
    EXPECT_TRUE(a.rig.cam2.T_world_device.isApprox(r.cam2.T_world_device, 0.0));
    const auto written = write_structured_light_capture("/proc/anascan-no-such/dir", a);
    ASSERT_FALSE(written.has_value());
    EXPECT_NE(written.error().message.find("/proc/anascan-no-such/dir"), std::string::npos);
    StructuredLightRenderConfig mismatch;
    mismatch.patterns.width_px = 1024;
    EXPECT_EQ(render_structured_light(*caster_, {}, r, mismatch).error().code,
              ErrorCode::kInvalidArgument);
}

TEST_F(StructuredLightTest, CalibrationFileHasTheStatueKeysAndOpenCvStereoConvention) {
    const StructuredLightRig r = rig(StructuredLightRigConfig{}, {});
    const std::filesystem::path path =
        std::filesystem::path(::testing::TempDir()) / "anascan_sim_calibration.yml";
    ASSERT_TRUE(write_stereo_calibration(path, r).has_value());
    cv::FileStorage fs(path.string(), cv::FileStorage::READ);
    ASSERT_TRUE(fs.isOpened());
    cv::Mat K1, K2, R, T, dist, P1, Q;
    fs["cam1_intrinsics"] >> K1;
    fs["cam2_intrinsics"] >> K2;
    fs["cam1_distorsion"] >> dist;
    const cv::FileNode size = fs["cam1_size"];
    fs["R"] >> R;
    fs["T"] >> T;
    fs["P1"] >> P1;
    fs["Q"] >> Q;
    EXPECT_EQ(size.size(), 2u);
    EXPECT_EQ(static_cast<int>(size[0]), 1600);
    EXPECT_EQ(static_cast<int>(size[1]), 1200);
    EXPECT_EQ(dist.total(), 5u);
    EXPECT_EQ(P1.rows, 3);
    EXPECT_EQ(Q.rows, 4);
    EXPECT_NEAR(cv::norm(T), 400.0, 1e-6);  // Millimetres.
    // X_cam2 = R X_cam1 + T for a world point.
    const Eigen::Vector3d p_world = r.cam1.T_world_device * Eigen::Vector3d(0.05, -0.02, 1.0);
    const Eigen::Vector3d p1 = r.cam1.T_world_device.inverse() * p_world;
    const Eigen::Vector3d p2 = r.cam2.T_world_device.inverse() * p_world;
    cv::Mat x1 = (cv::Mat_<double>(3, 1) << p1.x(), p1.y(), p1.z());
    const cv::Mat x2 = R * (1000.0 * x1) + T;
    for (int a = 0; a < 3; ++a) EXPECT_NEAR(x2.at<double>(a), 1000.0 * p2[a], 1e-6);
    EXPECT_NEAR(K1.at<double>(0, 0), 2700.0, 1e-9);
    EXPECT_EQ(cv::norm(K1, K2, cv::NORM_INF), 0.0);
    EXPECT_FALSE(write_stereo_calibration("/nonexistent-dir/calibration.yml", r).has_value());
}

}  // namespace
}  // namespace anascan::sim
