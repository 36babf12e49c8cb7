#pragma once
/// \file
/// The structured-light pipeline, in process: images of both cameras in, point cloud out.
/// Used by `anascan sl decode` (images from JPEG files) and by the simulated scanner
/// (rendered images). Pipeline: decode each camera (Gray code [+ phase shift]) ->
/// match cam1 pixels to cam2 through the projector coordinates -> triangulate.

#include <opencv2/core/mat.hpp>
#include <optional>
#include <span>
#include <vector>

#include "anascan/drivers/structured_light/gray_code.hpp"
#include "anascan/drivers/structured_light/phase_shift.hpp"
#include "anascan/drivers/structured_light/stereo_calibration.hpp"
#include "anascan/drivers/structured_light/stereo_matching.hpp"
#include "anascan/drivers/structured_light/triangulation.hpp"
#include "anascan/processing/core/expected.hpp"
#include "anascan/processing/core/point_cloud.hpp"

namespace anascan::drivers::sl {

/// What the projector showed, in order: the Gray-code sequence (OpenCV layout, ending with
/// white and black), then, when `phase` is set, the phase-shift images.
struct PatternSequence {
    GrayCodeLayout gray;
    std::optional<PhaseShiftLayout> phase;

    std::size_t image_count() const {
        return std::size_t(gray.image_count()) + (phase ? std::size_t(phase->image_count()) : 0);
    }
};

/// The projector images of the whole sequence (CV_8UC1, projector size), in order: what a
/// projector (real or simulated) shows and the cameras capture one by one.
std::vector<cv::Mat> make_patterns(const PatternSequence& sequence);

struct StereoDecodeConfig {
    PatternSequence sequence;
    GrayCodeDecodeConfig gray;
    PhaseShiftDecodeConfig phase;
    StereoMatchConfig match;
    TriangulationConfig triangulation;
};

/// The cloud and what happened to the pixels on the way.
struct StereoDecodeResult {
    /// cam1 frame, metres. intensity = cam1 white - black (grey levels); colors = cam1's
    /// white image (grey); confidence = 1 - ray_gap / max_ray_gap.
    PointCloud cloud;
    std::vector<float> ray_gap_m;      ///< Per point, metres.
    std::vector<cv::Point2i> cam1_px;  ///< Per point, the cam1 pixel it came from.
    std::size_t cam1_valid = 0;        ///< cam1 pixels with a valid code.
    std::size_t cam2_valid = 0;
    std::size_t matched = 0;  ///< cam1 pixels matched in cam2.
    std::size_t rejected_ray_gap = 0;
    std::size_t rejected_depth = 0;
    std::size_t pixel_count = 0;  ///< cam1 image pixels.
    double median_ray_gap_m = 0.0;
    double decode_s = 0.0;       ///< Wall time: decoding both cameras, seconds.
    double match_s = 0.0;        ///< Wall time: stereo matching, seconds.
    double triangulate_s = 0.0;  ///< Wall time: triangulation and the cloud, seconds.
};

/// Decodes one stereo capture. Images are CV_8UC1, `config.sequence.image_count()` per
/// camera, all of the size stored in the calibration. Errors (kInvalidArgument) say which
/// camera and image is wrong. Thread-safe; uses TBB; deterministic for any thread count.
Expected<StereoDecodeResult> decode_stereo(std::span<const cv::Mat> cam1_images,
                                           std::span<const cv::Mat> cam2_images,
                                           const StereoCalibration& calibration,
                                           const StereoDecodeConfig& config);

/// Decodes one camera's sequence into projector coordinates (Gray code, then phase).
Expected<ProjectorMap> decode_camera(std::span<const cv::Mat> images,
                                     const PatternSequence& sequence,
                                     const StereoDecodeConfig& config);

}  // namespace anascan::drivers::sl
