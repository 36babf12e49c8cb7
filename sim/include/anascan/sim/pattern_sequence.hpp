#pragma once
/// \file
/// The projector's pattern sequence: OpenCV structured_light::GrayCodePattern layout
/// (column codes then row codes, MSB first, each pattern followed by its inverse, then
/// all-white and all-black), followed by sinusoidal phase-shift patterns for sub-pixel
/// precision (columns, then rows).

#include <opencv2/core.hpp>
#include <vector>

#include "anascan/drivers/structured_light/stereo_decoder.hpp"

namespace anascan::sim {

struct PatternSequenceConfig {
    int width_px = 1280;  ///< Projector resolution.
    int height_px = 800;
    int phase_steps = 4;      ///< Shifts per axis, columns then rows (0: no phase patterns).
    int phase_period_px = 8;  ///< Sinusoid period in projector pixels.
};

/// The same sequence as the structured-light decoder describes it (drivers::sl): what
/// `decode_stereo` must be told to read a capture rendered with `config`.
drivers::sl::PatternSequence decoder_sequence(const PatternSequenceConfig& config);

enum class PatternKind { kGrayCode, kWhite, kBlack, kPhase };

/// One projected image. Gray code: bit `bit` (0 = MSB) of the reflected binary code of
/// the column (columns = true) or row index, inverted when `inverse`. Phase: value
/// 0.5 + 0.5 cos(2 pi c / period - 2 pi step / steps) of the column or row index c.
struct Pattern {
    PatternKind kind = PatternKind::kWhite;
    bool columns = true;
    int bit = 0;
    bool inverse = false;
    int step = 0;
};

/// Number of Gray-code bits for n projector columns (or rows): ceil(log2 n).
int gray_code_bits(int n);

/// The whole sequence in projection order.
std::vector<Pattern> pattern_sequence(const PatternSequenceConfig& config);

/// Brightness 0..1 that the pattern gives projector column (or row) `index`.
double pattern_level(const PatternSequenceConfig& config, const Pattern& pattern, int index);

/// The pattern as an 8-bit projector image (height x width), e.g. for a projector window.
/// The renderer projects drivers::sl::make_patterns(decoder_sequence(config)) (the same
/// images, phase levels rounded to 8 bits), so the decoder reads exactly what it expects.
cv::Mat projector_image(const PatternSequenceConfig& config, const Pattern& pattern);

}  // namespace anascan::sim
