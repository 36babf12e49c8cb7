#pragma once
/// \file
/// Sinusoidal phase shifting on top of Gray code: N shifted sinusoids of period P projector
/// pixels along the columns, then N along the rows. The Gray code gives the period index,
/// the phase the position inside the period (sub-pixel, independent of camera blur).

#include <opencv2/core/mat.hpp>
#include <span>
#include <vector>

#include "anascan/drivers/structured_light/gray_code.hpp"
#include "anascan/processing/core/expected.hpp"

namespace anascan::drivers::sl {

/// Sinusoid period and number of phase steps.
struct PhaseShiftLayout {
    int period_px = 16;  ///< Projector pixels per sinusoid period.
    int steps = 4;       ///< Shifts of 2*pi/steps; at least 3.

    int image_count() const { return 2 * steps; }
};

/// Projector images (CV_8UC1): I_n(x) = 127.5 (1 + cos(2 pi x / P - 2 pi n / N)) for the
/// column sinusoids (x = projector column), n = 0..N-1, then the same along the rows.
std::vector<cv::Mat> make_phase_shift_patterns(const GrayCodeLayout& layout,
                                               const PhaseShiftLayout& phase);

/// Validity rules of the phase decoder.
struct PhaseShiftDecodeConfig {
    float min_modulation = 8.0f;            ///< Sinusoid amplitude in the camera, grey levels.
    float max_gray_disagreement_px = 1.0f;  ///< |phase - Gray| position, projector pixels.
};

/// Replaces the Gray-code coordinates of `map` by unwrapped phase coordinates (same
/// convention: projector pixel centres at integers). Pixels whose modulation is too low or
/// whose phase disagrees with the Gray code become invalid. `images`: CV_8UC1,
/// `phase.image_count()` of them, the camera size.
Expected<void> refine_with_phase_shift(ProjectorMap& map, std::span<const cv::Mat> images,
                                       const PhaseShiftLayout& phase,
                                       const PhaseShiftDecodeConfig& config);

}  // namespace anascan::drivers::sl
