#include "anascan/sim/structured_light_renderer.hpp"

#include <tbb/parallel_for.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <opencv2/imgproc.hpp>
#include <string>

#include "hash_random.hpp"

namespace anascan::sim {
namespace {

constexpr float kNaN = std::numeric_limits<float>::quiet_NaN();
// Neighbours whose projector coordinates differ more than this lie across a depth edge
// and do not tell a pixel's footprint.
constexpr float kMaxFootprintPx = 8.0f;
// Shadow rays start this far from the surface so that they do not hit it again.
constexpr double kShadowOffsetM = 2e-5;

struct Scenery {
    const RayCaster& caster;
    const std::vector<float>& albedos;
    const PinholeModel& projector;
    const StructuredLightRenderConfig& config;
};

// Fills pixel (x, y) of `image`: the surface point seen, lit if the projector sees it.
void sample_pixel(const Scenery& s, const PinholeModel& cam, int x, int y, CameraSurface& image) {
    const Eigen::Vector3d origin = cam.T_world_device.translation();
    const Eigen::Vector3d dir = cam.ray_world(x, y);
    const auto hit = s.caster.cast(origin, dir);
    if (!hit) return;
    const Eigen::Vector3d p = origin + hit->distance_m * dir;
    const Eigen::Vector3d n =
        hit->normal.dot(dir) > 0.0 ? Eigen::Vector3d(-hit->normal) : hit->normal;
    image.albedo.at<float>(y, x) = s.albedos.empty() ? 0.5f : s.albedos[hit->triangle];
    image.truth.depth_m.at<float>(y, x) =
        static_cast<float>((cam.T_world_device.inverse() * p).z());
    const Eigen::Vector3d uvz = s.projector.project(p);
    const Eigen::Vector3d to_projector = s.projector.T_world_device.translation() - p;
    const double distance_m = to_projector.norm();
    const double cos_theta = n.dot(to_projector) / distance_m;
    if (uvz.z() <= 0.0 || cos_theta <= 0.0 || uvz.x() < -0.5 || uvz.y() < -0.5 ||
        uvz.x() > s.projector.width_px - 0.5 || uvz.y() > s.projector.height_px - 0.5)
        return;
    if (s.caster.occluded(p + kShadowOffsetM * n, to_projector / distance_m, 0.0,
                          distance_m - 2 * kShadowOffsetM))
        return;  // Projector shadow.
    const double falloff = s.config.reference_distance_m / distance_m;
    image.light.at<float>(y, x) = static_cast<float>(cos_theta * falloff * falloff);
    image.truth.projector_xy.at<cv::Vec2f>(y, x) =
        cv::Vec2f(static_cast<float>(uvz.x()), static_cast<float>(uvz.y()));
}

// Extent of each camera pixel in projector pixels, from neighbouring coordinates.
void estimate_footprints(CameraSurface& image) {
    const cv::Mat& xy = image.truth.projector_xy;
    auto delta = [&](int y, int x, int dy, int dx) -> cv::Vec2f {
        const int ny = y + dy, nx = x + dx;
        if (ny < 0 || nx < 0 || ny >= xy.rows || nx >= xy.cols) return {kNaN, kNaN};
        const cv::Vec2f d = xy.at<cv::Vec2f>(ny, nx) - xy.at<cv::Vec2f>(y, x);
        if (std::abs(d[0]) > kMaxFootprintPx || std::abs(d[1]) > kMaxFootprintPx)
            return {kNaN, kNaN};
        return d;
    };
    auto pick = [](cv::Vec2f a, cv::Vec2f b) { return std::isfinite(a[0]) ? a : b; };
    tbb::parallel_for(0, xy.rows, [&](int y) {
        for (int x = 0; x < xy.cols; ++x) {
            const cv::Vec2f dx = pick(delta(y, x, 0, 1), -delta(y, x, 0, -1));
            const cv::Vec2f dy = pick(delta(y, x, 1, 0), -delta(y, x, -1, 0));
            cv::Vec2f extent(1.0f, 1.0f);  // Unknown: about one projector pixel.
            if (std::isfinite(dx[0]) && std::isfinite(dy[0]))
                extent =
                    cv::Vec2f(std::abs(dx[0]) + std::abs(dy[0]), std::abs(dx[1]) + std::abs(dy[1]));
            image.footprint.at<cv::Vec2f>(y, x) = extent;
        }
    });
}

CameraSurface trace(const Scenery& s, const PinholeModel& cam) {
    const cv::Size size(cam.width_px, cam.height_px);
    CameraSurface image{.albedo = cv::Mat::zeros(size, CV_32F),
                        .light = cv::Mat::zeros(size, CV_32F),
                        .footprint = cv::Mat(size, CV_32FC2, cv::Scalar(1, 1)),
                        .truth = {.projector_xy = cv::Mat(size, CV_32FC2, cv::Scalar(kNaN, kNaN)),
                                  .depth_m = cv::Mat(size, CV_32F, cv::Scalar(kNaN))}};
    tbb::parallel_for(0, size.height, [&](int y) {
        for (int x = 0; x < size.width; ++x) sample_pixel(s, cam, x, y, image);
    });
    estimate_footprints(image);
    return image;
}

// A pattern along one projector axis, constant over each projector pixel
// [c - 0.5, c + 0.5) and zero outside, with its running integral for O(1) box filtering.
// The levels are the projector image's (drivers::sl::make_patterns: what the decoder
// expects), read along its first row (column patterns) or column (row patterns).
struct PatternProfile {
    std::vector<float> levels;
    std::vector<double> integral;  ///< integral[c] = sum of levels[0..c).

    PatternProfile(const cv::Mat& projector_image, bool columns)
        : levels(static_cast<std::size_t>(columns ? projector_image.cols : projector_image.rows)),
          integral(levels.size() + 1, 0.0) {
        for (std::size_t c = 0; c < levels.size(); ++c) {
            const int i = static_cast<int>(c);
            const std::uint8_t v = columns ? projector_image.at<std::uint8_t>(0, i)
                                           : projector_image.at<std::uint8_t>(i, 0);
            levels[c] = static_cast<float>(v) / 255.0f;
            integral[c + 1] = integral[c] + levels[c];
        }
    }

    // Integral of the pattern from -0.5 to x (projector pixel coordinates).
    double cumulative(double x) const {
        const double shifted = std::clamp(x + 0.5, 0.0, static_cast<double>(levels.size()));
        const auto c = std::min(static_cast<std::size_t>(shifted), levels.size() - 1);
        return integral[c] + (shifted - static_cast<double>(c)) * levels[c];
    }

    // Mean level over [centre - width / 2, centre + width / 2].
    float box_filtered(double centre, double width) const {
        return static_cast<float>(
            (cumulative(centre + 0.5 * width) - cumulative(centre - 0.5 * width)) / width);
    }
};

// How a projector image varies: along columns only (every row alike), rows only, or both.
enum class Stripes { kColumns, kRows, kNone };

Stripes stripes_of(const cv::Mat& image) {
    bool rows_alike = true, columns_alike = true;
    for (int y = 1; y < image.rows && rows_alike; ++y)
        rows_alike = std::equal(image.ptr(y), image.ptr(y) + image.cols, image.ptr(0));
    if (rows_alike) return Stripes::kColumns;
    for (int y = 0; y < image.rows && columns_alike; ++y)
        columns_alike = std::all_of(image.ptr(y), image.ptr(y) + image.cols,
                                    [&](std::uint8_t v) { return v == image.ptr(y)[0]; });
    return columns_alike ? Stripes::kRows : Stripes::kNone;
}

// Any projector image, constant over each projector pixel, with its summed-area table:
// the integral over [-0.5, x] x [-0.5, y] is bilinear inside each pixel, so the mean over
// any box is exact.
struct PatternArea {
    cv::Mat sat;  ///< CV_64F (rows + 1) x (cols + 1), cv::integral of the levels 0..1.

    explicit PatternArea(const cv::Mat& image) {
        if (image.empty()) return;
        cv::Mat levels;
        image.convertTo(levels, CV_64F, 1.0 / 255.0);
        cv::integral(levels, sat, CV_64F);
    }

    double cumulative(double x, double y) const {
        const double u = std::clamp(x + 0.5, 0.0, static_cast<double>(sat.cols - 1));
        const double v = std::clamp(y + 0.5, 0.0, static_cast<double>(sat.rows - 1));
        const int i = std::min(static_cast<int>(u), sat.cols - 2);
        const int j = std::min(static_cast<int>(v), sat.rows - 2);
        const double fu = u - i, fv = v - j;
        return (1 - fv) * ((1 - fu) * sat.at<double>(j, i) + fu * sat.at<double>(j, i + 1)) +
               fv * ((1 - fu) * sat.at<double>(j + 1, i) + fu * sat.at<double>(j + 1, i + 1));
    }

    float box_filtered(double cx, double cy, double wx, double wy) const {
        const double x0 = cx - 0.5 * wx, x1 = cx + 0.5 * wx;
        const double y0 = cy - 0.5 * wy, y1 = cy + 0.5 * wy;
        return static_cast<float>(
            (cumulative(x1, y1) - cumulative(x0, y1) - cumulative(x1, y0) + cumulative(x0, y0)) /
            (wx * wy));
    }
};

// The radiance (DN) of each pixel: ambient plus the pattern's level, box-filtered over the
// pixel's footprint widened by the projector blur, where lit. Stripes (every row alike:
// column patterns; every column alike: row patterns) go through a 1-D profile, any other
// image through its summed-area table.
cv::Mat radiance_of(const CameraSurface& surface, const StructuredLightRenderConfig& config,
                    const cv::Mat& projector_image) {
    const double blur_var = 12.0 * config.projector_blur_sigma_px * config.projector_blur_sigma_px;
    auto width = [&](double w) { return std::clamp(std::sqrt(w * w + blur_var), 0.05, 16.0); };
    const bool dark = projector_image.empty();
    const Stripes stripes = dark ? Stripes::kColumns : stripes_of(projector_image);
    const PatternProfile profile(dark ? cv::Mat(1, 1, CV_8UC1, cv::Scalar(0)) : projector_image,
                                 stripes != Stripes::kRows);
    const PatternArea area(stripes == Stripes::kNone ? projector_image : cv::Mat());
    const int axis = stripes == Stripes::kRows ? 1 : 0;
    cv::Mat radiance(surface.albedo.size(), CV_32F);
    tbb::parallel_for(0, radiance.rows, [&](int y) {
        for (int x = 0; x < radiance.cols; ++x) {
            const float light = surface.light.at<float>(y, x);
            float level = 0.0f;
            if (light > 0.0f) {
                const cv::Vec2f c = surface.truth.projector_xy.at<cv::Vec2f>(y, x);
                const cv::Vec2f w = surface.footprint.at<cv::Vec2f>(y, x);
                level = stripes == Stripes::kNone
                            ? area.box_filtered(c[0], c[1], width(w[0]), width(w[1]))
                            : profile.box_filtered(c[axis], width(w[axis]));
            }
            radiance.at<float>(y, x) =
                static_cast<float>(config.exposure_dn * surface.albedo.at<float>(y, x) *
                                   (config.ambient_level + light * level));
        }
    });
    return radiance;
}

}  // namespace

cv::Mat render_camera_image(const CameraSurface& surface, const cv::Mat& projector_image,
                            const StructuredLightRenderConfig& config, std::uint64_t noise_seed) {
    cv::Mat radiance = radiance_of(surface, config, projector_image);
    if (config.camera_blur_sigma_px > 0.0)
        cv::GaussianBlur(radiance, radiance, cv::Size(0, 0), config.camera_blur_sigma_px);
    cv::Mat image(radiance.size(), CV_8UC1);
    tbb::parallel_for(0, image.rows, [&](int y) {
        for (int x = 0; x < image.cols; ++x) {
            const double signal = radiance.at<float>(y, x);
            const double sigma = std::sqrt(config.read_noise_dn * config.read_noise_dn +
                                           config.shot_noise_dn2_per_dn * std::max(signal, 0.0));
            const double noise = sigma * detail::fast_normal_from_hash(detail::hash3(
                                             noise_seed, std::uint64_t(y) * image.cols + x));
            image.at<std::uint8_t>(y, x) =
                cv::saturate_cast<std::uint8_t>(signal + noise);  // Rounds.
        }
    });
    return image;
}

std::uint64_t camera_noise_seed(const StructuredLightRenderConfig& config, int camera_index,
                                std::size_t frame) {
    return detail::hash3(config.seed, static_cast<std::uint64_t>(camera_index), frame);
}

CameraSurface trace_camera_surface(const RayCaster& caster, const std::vector<float>& albedos,
                                   const PinholeModel& camera, const PinholeModel& projector,
                                   const StructuredLightRenderConfig& config) {
    return trace(Scenery{caster, albedos, projector, config}, camera);
}

namespace {

std::vector<cv::Mat> render_camera(const Scenery& s, const PinholeModel& cam,
                                   const std::vector<Pattern>& patterns,
                                   const std::vector<cv::Mat>& projector_images, int camera_index,
                                   CameraTruth& truth) {
    CameraSurface surface = trace(s, cam);
    std::vector<cv::Mat> images(patterns.size());
    tbb::parallel_for(std::size_t{0}, patterns.size(), [&](std::size_t i) {
        images[i] = render_camera_image(surface, projector_images[i], s.config,
                                        camera_noise_seed(s.config, camera_index, i));
    });
    truth = surface.truth;
    return images;
}

}  // namespace

Expected<StructuredLightCapture> render_structured_light(
    const RayCaster& caster, const std::vector<float>& albedo_of_triangle,
    const StructuredLightRig& rig, const StructuredLightRenderConfig& config) {
    if (rig.projector.width_px != config.patterns.width_px ||
        rig.projector.height_px != config.patterns.height_px)
        return fail(ErrorCode::kInvalidArgument,
                    "sim:structured-light: the projector resolution differs from the patterns'");
    if (config.patterns.phase_steps != 0 &&
        (config.patterns.phase_steps < 3 || config.patterns.phase_period_px < 2))
        return fail(ErrorCode::kInvalidArgument,
                    "sim:structured-light: phase shifting needs >= 3 steps and a period >= 2 px");
    if (rig.cam1.width_px <= 0 || rig.cam1.height_px <= 0 || rig.cam2.width_px <= 0 ||
        rig.cam2.height_px <= 0)
        return fail(ErrorCode::kInvalidArgument, "sim:structured-light: empty camera image size");
    const Scenery scenery{caster, albedo_of_triangle, rig.projector, config};
    StructuredLightCapture capture{
        .rig = rig, .patterns = pattern_sequence(config.patterns), .layout = config.patterns};
    const std::vector<cv::Mat> projector_images =
        drivers::sl::make_patterns(decoder_sequence(config.patterns));
    if (projector_images.size() != capture.patterns.size())
        return fail(ErrorCode::kInvalidArgument,
                    "sim:structured-light: the decoder's pattern sequence has " +
                        std::to_string(projector_images.size()) + " images, the sim's " +
                        std::to_string(capture.patterns.size()));
    capture.cam1 =
        render_camera(scenery, rig.cam1, capture.patterns, projector_images, 1, capture.truth1);
    capture.cam2 =
        render_camera(scenery, rig.cam2, capture.patterns, projector_images, 2, capture.truth2);
    return capture;
}

}  // namespace anascan::sim
