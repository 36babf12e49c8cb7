#include "anascan/gui/scan_colors.hpp"

#include <algorithm>
#include <cmath>

namespace anascan::gui {
namespace {

std::uint8_t to_byte(double v) {
    return static_cast<std::uint8_t>(std::lround(255.0 * std::clamp(v, 0.0, 1.0)));
}

/// HSV with full saturation and value 0.95, hue in turns (0..1).
Rgb8 hue_color(double hue_turns) {
    const double h = 6.0 * (hue_turns - std::floor(hue_turns));
    const double x = 1.0 - std::abs(std::fmod(h, 2.0) - 1.0);
    double r = 0.0, g = 0.0, b = 0.0;
    switch (static_cast<int>(h)) {
        case 0:
            r = 1;
            g = x;
            break;
        case 1:
            r = x;
            g = 1;
            break;
        case 2:
            g = 1;
            b = x;
            break;
        case 3:
            g = x;
            b = 1;
            break;
        case 4:
            r = x;
            b = 1;
            break;
        default:
            r = 1;
            b = x;
            break;
    }
    const double v = 0.95;
    // Lift the darkest channel a little so that no colour is too dark on a black view.
    return {to_byte(0.25 + 0.75 * r * v), to_byte(0.25 + 0.75 * g * v),
            to_byte(0.25 + 0.75 * b * v)};
}

}  // namespace

Rgb8 scan_palette_color(std::int64_t seq) {
    constexpr double kGoldenTurns = 0.6180339887498949;
    return hue_color(0.1 + kGoldenTurns * static_cast<double>(seq));
}

Rgb8 quality_color(const ScanRow& row) {
    switch (row.state) {
        case ScanRowState::kFailed:
            return {230, 40, 30};
        case ScanRowState::kFlagged:
            return {230, 60, 220};  // out of the model: drawn only when selected
        case ScanRowState::kQueued:
        case ScanRowState::kExcluded:
            return {120, 120, 120};
        case ScanRowState::kUnjoined:
            return {90, 180, 255};  // as the scan list's "unjoined"
        case ScanRowState::kRegistered:
            break;
    }
    if (!row.rms_mm) return {60, 200, 80};
    if (*row.rms_mm < 0.5) return {60, 200, 80};
    if (*row.rms_mm < 1.5) return {240, 210, 40};
    return {250, 130, 30};
}

}  // namespace anascan::gui
