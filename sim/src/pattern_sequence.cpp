#include "anascan/sim/pattern_sequence.hpp"

#include <cmath>
#include <numbers>

namespace anascan::sim {

int gray_code_bits(int n) {
    int bits = 0;
    while ((1 << bits) < n) ++bits;
    return bits;
}

drivers::sl::PatternSequence decoder_sequence(const PatternSequenceConfig& config) {
    drivers::sl::PatternSequence sequence{
        .gray = {.projector_width_px = config.width_px, .projector_height_px = config.height_px}};
    if (config.phase_steps > 0)
        sequence.phase = drivers::sl::PhaseShiftLayout{.period_px = config.phase_period_px,
                                                       .steps = config.phase_steps};
    return sequence;
}

std::vector<Pattern> pattern_sequence(const PatternSequenceConfig& config) {
    std::vector<Pattern> sequence;
    for (const bool columns : {true, false}) {
        const int bits = gray_code_bits(columns ? config.width_px : config.height_px);
        for (int bit = 0; bit < bits; ++bit) {
            sequence.push_back({.kind = PatternKind::kGrayCode, .columns = columns, .bit = bit});
            sequence.push_back(
                {.kind = PatternKind::kGrayCode, .columns = columns, .bit = bit, .inverse = true});
        }
    }
    sequence.push_back({.kind = PatternKind::kWhite});
    sequence.push_back({.kind = PatternKind::kBlack});
    for (const bool columns : {true, false}) {
        for (int step = 0; step < config.phase_steps; ++step)
            sequence.push_back({.kind = PatternKind::kPhase, .columns = columns, .step = step});
    }
    return sequence;
}

double pattern_level(const PatternSequenceConfig& config, const Pattern& pattern, int index) {
    switch (pattern.kind) {
        case PatternKind::kWhite:
            return 1.0;
        case PatternKind::kBlack:
            return 0.0;
        case PatternKind::kGrayCode: {
            const int bits = gray_code_bits(pattern.columns ? config.width_px : config.height_px);
            const int gray = index ^ (index >> 1);
            const int value = (gray >> (bits - 1 - pattern.bit)) & 1;
            return (value != 0) != pattern.inverse ? 1.0 : 0.0;
        }
        case PatternKind::kPhase: {
            const double phase = 2.0 * std::numbers::pi *
                                 (index / static_cast<double>(config.phase_period_px) -
                                  static_cast<double>(pattern.step) / config.phase_steps);
            return 0.5 + 0.5 * std::cos(phase);
        }
    }
    return 0.0;
}

cv::Mat projector_image(const PatternSequenceConfig& config, const Pattern& pattern) {
    cv::Mat image(config.height_px, config.width_px, CV_8UC1);
    for (int row = 0; row < config.height_px; ++row) {
        for (int col = 0; col < config.width_px; ++col) {
            const double level = pattern_level(config, pattern, pattern.columns ? col : row);
            image.at<std::uint8_t>(row, col) = cv::saturate_cast<std::uint8_t>(255.0 * level);
        }
    }
    return image;
}

}  // namespace anascan::sim
