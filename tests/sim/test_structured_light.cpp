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

namespace anascan::sim {
namespace {

// Cameras with the full rig's focal length but a small sensor crop: same pixel footprint
// on the stone as the 1600x1200 default, a fraction of the rendering time.
StructuredLightRigConfig narrow_rig() {
    return StructuredLightRigConfig{.camera_width_px = 240, .camera_height_px = 180};
}

class StructuredLightTest : public testing::SmallSceneSuite {
protected:
    static StructuredLightRig rig(const StructuredLightRigConfig& config, const Viewpoint& view) {
        const Eigen::Vector3d target = scene_->T_world_block.translation() +
                                       Eigen::Vector3d(0, 0, 0.5 * scene_->block_size_m.z());
        return make_structured_light_rig(config, sensor_looking_at(target, view));
    }
    static StructuredLightCapture render(const StructuredLightRig& r,
                                         const StructuredLightRenderConfig& config = {}) {
        return render_structured_light(*caster_, triangle_albedos(*scene_), r, config).value();
    }
};

// What the ray geometry says camera pixel (x, y) sees: the projector pixel coordinates of
// the surface point, or nothing when the projector does not light it.
std::optional<Eigen::Vector2d> lit_projector_xy(const RayCaster& caster,
                                                const StructuredLightRig& rig,
                                                const PinholeModel& cam, int x, int y) {
    const Eigen::Vector3d o = cam.T_world_device.translation(), d = cam.ray_world(x, y);
    const auto hit = caster.cast(o, d);
    if (!hit) return std::nullopt;
    const Eigen::Vector3d p = o + hit->distance_m * d;
    const Eigen::Vector3d uvz = rig.projector.project(p);
    const Eigen::Vector3d to_proj = rig.projector.T_world_device.translation() - p;
    if (uvz.z() <= 0 || uvz.x() < 0 || uvz.y() < 0 || uvz.x() > rig.projector.width_px - 1 ||
        uvz.y() > rig.projector.height_px - 1)
        return std::nullopt;
    if (caster.occluded(p, to_proj.normalized(), 1e-4, to_proj.norm() - 1e-4)) return std::nullopt;
    return Eigen::Vector2d(uvz.x(), uvz.y());
}

// Cosine between a surface normal and the direction to the projector.
double facing_projector(const StructuredLightRig& rig, const Eigen::Vector3d& p,
                        const Eigen::Vector3d& n) {
    return n.dot((rig.projector.T_world_device.translation() - p).normalized());
}

// Reference decode of one Gray-coded axis at a pixel (OpenCV layout, MSB first).
int decode_gray(const std::vector<cv::Mat>& images, int first, int bits, int x, int y) {
    int gray = 0;
    for (int k = 0; k < bits; ++k) {
        const int pattern = images[first + 2 * k].at<std::uint8_t>(y, x);
        const int inverse = images[first + 2 * k + 1].at<std::uint8_t>(y, x);
        gray = (gray << 1) | (pattern > inverse ? 1 : 0);
    }
    int binary = gray;
    for (int shift = 1; shift < bits; shift <<= 1) binary ^= binary >> shift;
    return binary;
}

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

namespace anascan::sim {
namespace {

// Projector column (columns = true) or row of a camera pixel from the images: Gray code for
// the integer part, the phase shifts for the fraction (unwrapped against the Gray code).
double decode_axis(const std::vector<cv::Mat>& images, const PatternSequenceConfig& pc,
                   bool columns, int x, int y) {
    const int col_bits = gray_code_bits(pc.width_px), row_bits = gray_code_bits(pc.height_px);
    const int code = columns ? decode_gray(images, 0, col_bits, x, y)
                             : decode_gray(images, 2 * col_bits, row_bits, x, y);
    const int first_phase = 2 * (col_bits + row_bits) + 2 + (columns ? 0 : pc.phase_steps);
    double s = 0.0, co = 0.0;
    for (int k = 0; k < pc.phase_steps; ++k) {
        const double v = images[first_phase + k].at<std::uint8_t>(y, x);
        s += v * std::sin(2.0 * std::numbers::pi * k / pc.phase_steps);
        co += v * std::cos(2.0 * std::numbers::pi * k / pc.phase_steps);
    }
    const double P = pc.phase_period_px;
    const double fraction = std::atan2(s, co) / (2.0 * std::numbers::pi) * P;  // Code mod P.
    return fraction + P * std::round((code - fraction) / P);
}

double decode_column(const std::vector<cv::Mat>& images, const PatternSequenceConfig& pc, int x,
                     int y) {
    return decode_axis(images, pc, true, x, y);
}

// Camera-projector triangulation (the camera ray against the plane of projector column u)
// from the rendered images, against the true surface: the code precision the stereo decoder
// builds on. The projector is only half the stereo baseline from a camera, so this is the
// harder geometry.
TEST_F(StructuredLightTest, CodesTriangulateWithinTheAccuracyBudgetAtOneMetre) {
    const StructuredLightRig r = rig(narrow_rig(), {.azimuth_deg = 10, .elevation_deg = 60});
    const StructuredLightRenderConfig config;
    const StructuredLightCapture capture = render(r, config);
    const Pose T_proj_world = r.projector.T_world_device.inverse();
    std::vector<double> errors;
    for (int y = 0; y < r.cam1.height_px; ++y) {
        for (int x = 0; x < r.cam1.width_px; ++x) {
            if (!lit_projector_xy(*caster_, r, r.cam1, x, y)) continue;
            const Eigen::Vector3d o_w = r.cam1.T_world_device.translation(),
                                  d_w = r.cam1.ray_world(x, y);
            const double truth = caster_->cast(o_w, d_w)->distance_m;
            const double a =
                (decode_column(capture.cam1, config.patterns, x, y) - r.projector.cx_px) /
                r.projector.fx_px;
            const Eigen::Vector3d o = T_proj_world * o_w, d = T_proj_world.linear() * d_w;
            const double t = (a * o.z() - o.x()) / (d.x() - a * d.z());
            errors.push_back(std::abs(t - truth));
        }
    }
    ASSERT_GT(errors.size(), 20000u);
    std::sort(errors.begin(), errors.end());
    const double within =
        static_cast<double>(std::lower_bound(errors.begin(), errors.end(), 0.0003) -
                            errors.begin()) /
        errors.size();
    double sum2 = 0.0;
    for (std::size_t i = 0; i < errors.size() * 95 / 100; ++i) sum2 += errors[i] * errors[i];
    std::printf(
        "camera-projector: %.2f %% of %zu points within 0.3 mm, median %.3f mm, RMS of the "
        "best 95 %% %.3f mm\n",
        100.0 * within, errors.size(), 1000.0 * errors[errors.size() / 2],
        1000.0 * std::sqrt(sum2 / (errors.size() * 95 / 100)));
    EXPECT_GT(within, 0.95);
}

// Where in camera 2 the projector code (u, v) lies, from a local affine fit of the decoded
// codes around (x0, y0); nullopt across a depth edge or off the image.
std::optional<Eigen::Vector2d> locate_code(const cv::Mat& u2, const cv::Mat& v2, int x0, int y0,
                                           const Eigen::Vector2d& code) {
    Eigen::Matrix3d ata = Eigen::Matrix3d::Zero();
    Eigen::Matrix<double, 3, 2> atb = Eigen::Matrix<double, 3, 2>::Zero();
    for (int dy = -1; dy <= 1; ++dy) {
        for (int dx = -1; dx <= 1; ++dx) {
            const int x = x0 + dx, y = y0 + dy;
            if (x < 0 || y < 0 || x >= u2.cols || y >= u2.rows) return std::nullopt;
            const double u = u2.at<double>(y, x), v = v2.at<double>(y, x);
            if (!std::isfinite(u) || std::abs(u - code.x()) > 4 || std::abs(v - code.y()) > 4)
                return std::nullopt;
            const Eigen::Vector3d a(1.0, dx, dy);
            ata += a * a.transpose();
            atb += a * Eigen::RowVector2d(u, v);
        }
    }
    const Eigen::Matrix<double, 3, 2> fit = ata.ldlt().solve(atb);  // Rows: offset, d/dx, d/dy.
    const Eigen::Matrix2d J = fit.bottomRows<2>().transpose();
    const Eigen::Vector2d offset = J.inverse() * (code - fit.row(0).transpose());
    return Eigen::Vector2d(x0 + offset.x(), y0 + offset.y());
}

// Midpoint of the shortest segment between two rays (unit directions).
Eigen::Vector3d ray_midpoint(const Eigen::Vector3d& o1, const Eigen::Vector3d& d1,
                             const Eigen::Vector3d& o2, const Eigen::Vector3d& d2) {
    const Eigen::Vector3d w = o1 - o2;
    const double b = d1.dot(d2), d = d1.dot(w), e = d2.dot(w), denom = 1.0 - b * b;
    const double t1 = (b * e - d) / denom, t2 = (e - b * d) / denom;
    return 0.5 * (o1 + t1 * d1 + o2 + t2 * d2);
}

// Stereo: each camera-1 pixel's decoded code is found in camera 2 (sub-pixel, by a local
// fit of camera 2's decoded codes; the true point only tells where to look) and the two
// camera rays are triangulated - the path of the real decoder, without rectification.
TEST_F(StructuredLightTest, StereoCodesTriangulateWithinTheAccuracyBudgetAtOneMetre) {
    const StructuredLightRig r = rig(narrow_rig(), {.azimuth_deg = 10, .elevation_deg = 60});
    const StructuredLightRenderConfig config;
    const StructuredLightCapture capture = render(r, config);
    cv::Mat u2(r.cam2.height_px, r.cam2.width_px, CV_64F, cv::Scalar(NAN)), v2 = u2.clone();
    for (int y = 0; y < u2.rows; ++y) {
        for (int x = 0; x < u2.cols; ++x) {
            if (capture.cam2[42].at<std::uint8_t>(y, x) - capture.cam2[43].at<std::uint8_t>(y, x) <
                20)
                continue;
            u2.at<double>(y, x) = decode_axis(capture.cam2, config.patterns, true, x, y);
            v2.at<double>(y, x) = decode_axis(capture.cam2, config.patterns, false, x, y);
        }
    }
    std::vector<double> errors;
    for (int y = 0; y < r.cam1.height_px; ++y) {
        for (int x = 0; x < r.cam1.width_px; ++x) {
            if (!lit_projector_xy(*caster_, r, r.cam1, x, y)) continue;
            const Eigen::Vector3d o1 = r.cam1.T_world_device.translation(),
                                  d1 = r.cam1.ray_world(x, y);
            const Eigen::Vector3d p = o1 + caster_->cast(o1, d1)->distance_m * d1;
            const Eigen::Vector3d seen_by_2 = r.cam2.project(p);
            const Eigen::Vector2d code(decode_axis(capture.cam1, config.patterns, true, x, y),
                                       decode_axis(capture.cam1, config.patterns, false, x, y));
            const auto xy2 = locate_code(u2, v2, static_cast<int>(std::lround(seen_by_2.x())),
                                         static_cast<int>(std::lround(seen_by_2.y())), code);
            if (!xy2) continue;
            const Eigen::Vector3d o2 = r.cam2.T_world_device.translation();
            errors.push_back(
                (ray_midpoint(o1, d1, o2, r.cam2.ray_world(xy2->x(), xy2->y())) - p).norm());
        }
    }
    ASSERT_GT(errors.size(), 20000u);
    std::sort(errors.begin(), errors.end());
    const double within =
        static_cast<double>(std::lower_bound(errors.begin(), errors.end(), 0.0003) -
                            errors.begin()) /
        errors.size();
    std::printf("stereo: %.2f %% of %zu points within 0.3 mm of the true point, median %.3f mm\n",
                100.0 * within, errors.size(), 1000.0 * errors[errors.size() / 2]);
    EXPECT_GT(within, 0.95);
}

// render_camera_image lights each pixel with the projector image's mean over the pixel's
// footprint: with footprints of exactly one projector pixel centred on it, no blur and
// no noise, a pixel shows exactly the projector pixel it looks at, for stripe patterns
// (1-D profile) and for any other image (summed-area table) alike; a dark projector
// leaves the ambient light.
TEST(RenderCameraImage, EachPixelShowsTheProjectorPixelItLooksAt) {
    const int w = 12, h = 8;
    CameraSurface surface{.albedo = cv::Mat(h, w, CV_32F, cv::Scalar(1.0f)),
                          .light = cv::Mat(h, w, CV_32F, cv::Scalar(1.0f)),
                          .footprint = cv::Mat(h, w, CV_32FC2, cv::Scalar(1.0f, 1.0f)),
                          .truth = {.projector_xy = cv::Mat(h, w, CV_32FC2)}};
    for (int y = 0; y < h; ++y)
        for (int x = 0; x < w; ++x)
            surface.truth.projector_xy.at<cv::Vec2f>(y, x) = cv::Vec2f(float(w - 1 - x), float(y));
    const StructuredLightRenderConfig config{.exposure_dn = 255.0,
                                             .ambient_level = 0.0,
                                             .read_noise_dn = 0.0,
                                             .shot_noise_dn2_per_dn = 0.0,
                                             .camera_blur_sigma_px = 0.0,
                                             .projector_blur_sigma_px = 0.0};
    cv::Mat any(h, w, CV_8UC1), stripes(h, w, CV_8UC1);
    for (int y = 0; y < h; ++y)
        for (int x = 0; x < w; ++x) {
            any.at<std::uint8_t>(y, x) = static_cast<std::uint8_t>((37 * x + 91 * y) % 256);
            stripes.at<std::uint8_t>(y, x) = static_cast<std::uint8_t>(20 * x);
        }
    for (const cv::Mat& projector : {any, stripes}) {
        const cv::Mat image = render_camera_image(surface, projector, config, 7);
        for (int y = 0; y < h; ++y)
            for (int x = 0; x < w; ++x)
                ASSERT_EQ(image.at<std::uint8_t>(y, x), projector.at<std::uint8_t>(y, w - 1 - x))
                    << "pixel (" << x << ", " << y << ")";
    }
    cv::Mat rows(h, w, CV_8UC1);  // row stripes: every column alike
    for (int y = 0; y < h; ++y) rows.row(y).setTo(cv::Scalar(30 * y));
    const cv::Mat lit_by_rows = render_camera_image(surface, rows, config, 7);
    for (int y = 0; y < h; ++y) EXPECT_EQ(lit_by_rows.at<std::uint8_t>(y, 3), 30 * y);
    StructuredLightRenderConfig ambient = config;
    ambient.ambient_level = 0.2;
    const cv::Mat dark = render_camera_image(surface, cv::Mat(), ambient, 7);
    EXPECT_EQ(cv::countNonZero(dark != 51), 0);  // 255 * 0.2
}

}  // namespace
}  // namespace anascan::sim
