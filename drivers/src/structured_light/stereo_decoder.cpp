#include "anascan/drivers/structured_light/stereo_decoder.hpp"

#include <algorithm>
#include <opencv2/core.hpp>
#include <string>

#include "anascan/processing/core/stopwatch.hpp"

namespace anascan::drivers::sl {
namespace {

Expected<void> check_size(std::span<const cv::Mat> images, const CameraIntrinsics& cam,
                          const std::string& name) {
    if (images.empty()) return fail(ErrorCode::kEmpty, name + ": no images");
    const cv::Mat& im = images[0];
    if (im.cols != cam.width_px || im.rows != cam.height_px) {
        return fail(ErrorCode::kInvalidArgument,
                    name + " images are " + std::to_string(im.cols) + "x" +
                        std::to_string(im.rows) + " px but the calibration is for " +
                        std::to_string(cam.width_px) + "x" + std::to_string(cam.height_px) + " px");
    }
    return {};
}

Expected<ProjectorMap> decode_named(std::span<const cv::Mat> images,
                                    const StereoDecodeConfig& config, const std::string& name) {
    if (auto ok = check_image_sequence(images, config.sequence.image_count(), name); !ok)
        return fail(ok.error());
    return decode_camera(images, config.sequence, config);
}

void fill_cloud(const StereoMatches& matches, const TriangulatedPoints& points,
                const ProjectorMap& cam1, const StereoDecodeConfig& config,
                StereoDecodeResult& result) {
    PointCloud& cloud = result.cloud;
    const auto ok =
        std::size_t(std::count(points.status.begin(), points.status.end(), PointStatus::kOk));
    cloud.positions.reserve(ok);
    cloud.intensity.reserve(ok);
    cloud.colors.reserve(ok);
    cloud.confidence.reserve(ok);
    result.ray_gap_m.reserve(ok);
    result.cam1_px.reserve(ok);
    for (std::size_t i = 0; i < points.status.size(); ++i) {
        if (points.status[i] == PointStatus::kRayGap) ++result.rejected_ray_gap;
        if (points.status[i] == PointStatus::kDepth) ++result.rejected_depth;
        if (points.status[i] != PointStatus::kOk) continue;
        const cv::Point2i px = matches.cam1_px[i];
        const std::uint8_t grey = cam1.white.at<std::uint8_t>(px.y, px.x);
        cloud.positions.push_back(points.position_m[i]);
        cloud.intensity.push_back(float(cam1.contrast.at<std::uint8_t>(px.y, px.x)));
        cloud.colors.push_back({grey, grey, grey});
        const double gap = points.ray_gap_m[i];
        cloud.confidence.push_back(
            float(std::clamp(1.0 - gap / config.triangulation.max_ray_gap_m, 0.0, 1.0)));
        result.ray_gap_m.push_back(points.ray_gap_m[i]);
        result.cam1_px.push_back(px);
    }
    if (!result.ray_gap_m.empty()) {
        std::vector<float> gaps = result.ray_gap_m;
        auto mid = gaps.begin() + std::ptrdiff_t(gaps.size() / 2);
        std::nth_element(gaps.begin(), mid, gaps.end());
        result.median_ray_gap_m = *mid;
    }
}

}  // namespace

std::vector<cv::Mat> make_patterns(const PatternSequence& sequence) {
    std::vector<cv::Mat> patterns = make_gray_code_patterns(sequence.gray);
    if (sequence.phase) {
        for (cv::Mat& p : make_phase_shift_patterns(sequence.gray, *sequence.phase))
            patterns.push_back(std::move(p));
    }
    return patterns;
}

Expected<ProjectorMap> decode_camera(std::span<const cv::Mat> images,
                                     const PatternSequence& sequence,
                                     const StereoDecodeConfig& config) {
    const std::size_t gray_count = std::size_t(sequence.gray.image_count());
    if (images.size() < gray_count)
        return fail(ErrorCode::kInvalidArgument, "fewer images than the Gray code needs");
    auto map = decode_gray_code(images.first(gray_count), sequence.gray, config.gray);
    if (!map || !sequence.phase) return map;
    if (auto ok = refine_with_phase_shift(*map, images.subspan(gray_count), *sequence.phase,
                                          config.phase);
        !ok)
        return fail(ok.error());
    return map;
}

Expected<StereoDecodeResult> decode_stereo(std::span<const cv::Mat> cam1_images,
                                           std::span<const cv::Mat> cam2_images,
                                           const StereoCalibration& calibration,
                                           const StereoDecodeConfig& config) {
    if (auto ok = check_size(cam1_images, calibration.cam1, "cam1"); !ok) return fail(ok.error());
    if (auto ok = check_size(cam2_images, calibration.cam2, "cam2"); !ok) return fail(ok.error());
    StereoDecodeResult result;
    Stopwatch stages;
    auto map1 = decode_named(cam1_images, config, "cam1");
    if (!map1) return fail(map1.error());
    auto map2 = decode_named(cam2_images, config, "cam2");
    if (!map2) return fail(map2.error());
    result.decode_s = stages.lap();
    const StereoMatches matches =
        match_projector_maps(*map1, *map2, config.sequence.gray, config.match);
    result.match_s = stages.lap();
    const TriangulatedPoints points =
        triangulate_matches(matches, calibration, config.triangulation);
    result.cam1_valid = map1->valid_count;
    result.cam2_valid = map2->valid_count;
    result.matched = matches.cam1_px.size();
    result.pixel_count = map1->column_px.total();
    fill_cloud(matches, points, *map1, config, result);
    result.triangulate_s = stages.lap();
    return result;
}

}  // namespace anascan::drivers::sl
