// Triangulation from the simulated structured-light images against the true surface, and
// the camera images' projector pixels.
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
