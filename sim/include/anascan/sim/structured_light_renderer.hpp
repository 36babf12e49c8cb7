#pragma once
/// \file
/// Simulated structured-light capture: the projector's patterns rendered onto a scene and
/// imaged by the two cameras of a rig, with ambient light, projector shadows, occlusion,
/// projector and camera blur, projector pixel quantisation and sensor noise.

#include <cstdint>
#include <filesystem>
#include <opencv2/core.hpp>
#include <vector>

#include "anascan/processing/core/expected.hpp"
#include "anascan/sim/pattern_sequence.hpp"
#include "anascan/sim/ray_caster.hpp"
#include "anascan/sim/structured_light_rig.hpp"

namespace anascan::sim {

/// Photometry (camera digital numbers, DN, 8-bit) and noise. A surface of albedo a whose
/// normal makes angle theta with the direction to the projector at distance d shows
/// exposure_dn * a * (ambient_level + cos(theta) * (reference_distance_m / d)^2 * pattern).
struct StructuredLightRenderConfig {
    PatternSequenceConfig patterns;
    double exposure_dn = 230.0;
    double ambient_level = 0.08;  ///< Tent light, relative to the projector's white.
    double reference_distance_m = 1.0;
    double read_noise_dn = 1.0;            ///< Gaussian sensor noise, DN.
    double shot_noise_dn2_per_dn = 0.02;   ///< Photon noise variance per DN of signal.
    double camera_blur_sigma_px = 0.5;     ///< Lens blur, camera pixels (Gaussian).
    double projector_blur_sigma_px = 0.4;  ///< Projector defocus, projector pixels.
    std::uint64_t seed = 1;                ///< Same scene, rig and config: identical images.
};

/// What each camera pixel truly sees (for tests and accuracy checks).
struct CameraTruth {
    cv::Mat projector_xy;  ///< CV_32FC2: projector pixel lighting the surface seen; NaN if unlit.
    cv::Mat depth_m;       ///< CV_32F: z of the surface point in the camera frame; NaN: none.
};

/// What one camera sees of the scene from one pose, per pixel: traced once, then rendered
/// under any projector image (render_camera_image).
struct CameraSurface {
    cv::Mat albedo;     ///< CV_32F, 0 where nothing is hit.
    cv::Mat light;      ///< CV_32F: cos(theta) (d_ref / d)^2, 0 where unlit or in shadow.
    cv::Mat footprint;  ///< CV_32FC2: extent of the pixel in projector columns and rows.
    CameraTruth truth;
};

/// Ray-casts every pixel of `camera` and the shadow ray toward `projector` (TBB).
CameraSurface trace_camera_surface(const RayCaster& caster, const std::vector<float>& albedos,
                                   const PinholeModel& camera, const PinholeModel& projector,
                                   const StructuredLightRenderConfig& config);

/// The camera image (CV_8UC1) of the surface lit by `projector_image` (CV_8UC1, projector
/// size; empty: the projector is dark) and the ambient light: each pixel takes the image's
/// mean over its footprint (exact box filter of the projector pixels), then camera blur and
/// noise drawn from `noise_seed`. Thread-safe; TBB over rows.
cv::Mat render_camera_image(const CameraSurface& surface, const cv::Mat& projector_image,
                            const StructuredLightRenderConfig& config, std::uint64_t noise_seed);

/// The noise seed of camera `camera_index`'s `frame`-th image of a capture.
std::uint64_t camera_noise_seed(const StructuredLightRenderConfig& config, int camera_index,
                                std::size_t frame);

struct StructuredLightCapture {
    StructuredLightRig rig;         ///< The rig with its true poses (T_world_device).
    std::vector<Pattern> patterns;  ///< In projection order.
    PatternSequenceConfig layout;   ///< The sequence they come from.
    std::vector<cv::Mat> cam1;      ///< CV_8UC1 images, one per pattern.
    std::vector<cv::Mat> cam2;
    CameraTruth truth1, truth2;
};

/// Renders every pattern of the sequence as seen by both cameras of the rig. The rig's
/// projector must have config.patterns' resolution (kInvalidArgument otherwise).
Expected<StructuredLightCapture> render_structured_light(
    const RayCaster& caster, const std::vector<float>& albedo_of_triangle,
    const StructuredLightRig& rig, const StructuredLightRenderConfig& config = {});

/// Writes the capture as `dir/pattern_cam{1,2}_imNN.png` (NN from 01, projection order)
/// and its rig's calibration, with the pattern layout, as `dir/calibration.yml` (so that
/// `anascan sl decode` needs no layout flags); creates `dir` if needed.
Expected<void> write_structured_light_capture(const std::filesystem::path& dir,
                                              const StructuredLightCapture& capture);

}  // namespace anascan::sim
