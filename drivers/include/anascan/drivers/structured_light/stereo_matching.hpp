#pragma once
/// \file
/// Stereo correspondence through decoded projector coordinates: for every valid cam1 pixel,
/// the sub-pixel cam2 position that decoded the same projector coordinates.

#include <opencv2/core/types.hpp>
#include <vector>

#include "anascan/drivers/structured_light/gray_code.hpp"

namespace anascan::drivers::sl {

struct StereoMatchConfig {
    int max_iterations = 4;          ///< Newton steps when inverting cam2's projector map.
    float min_jacobian_det = 0.02f;  ///< |det d(projector)/d(cam2 pixel)|, px^2/px^2.
    /// Largest ratio (either way) between the projector areas one cam2 and one cam1 pixel
    /// cover: a surface one camera sees at a grazing angle (typically a hole wall next to
    /// a projector shadow) is matched unreliably there and its points leave the surface
    /// by millimetres with small ray gaps. 0 disables the check.
    float max_foreshortening_ratio = 4.0f;
};

/// Matched pixel pairs, in cam1 row-major order (deterministic for any thread count).
struct StereoMatches {
    std::vector<cv::Point2i> cam1_px;  ///< Integer cam1 pixel.
    std::vector<cv::Point2f> cam2_px;  ///< Sub-pixel cam2 position, pixels.
    std::size_t cam1_valid = 0;        ///< Valid cam1 pixels (candidates).
};

/// Inverts cam2's projector map locally (Newton steps on its finite-difference Jacobian,
/// starting at the cam2 pixel whose code is nearest) at each valid cam1 pixel's projector
/// coordinates. `projector` gives the size of the code space.
StereoMatches match_projector_maps(const ProjectorMap& cam1, const ProjectorMap& cam2,
                                   const GrayCodeLayout& projector,
                                   const StereoMatchConfig& config);

}  // namespace anascan::drivers::sl
