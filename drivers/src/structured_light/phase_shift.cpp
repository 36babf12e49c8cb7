#include "anascan/drivers/structured_light/phase_shift.hpp"

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include <cmath>
#include <cstdint>
#include <limits>
#include <numbers>
#include <opencv2/core.hpp>

namespace anascan::drivers::sl {
namespace {

constexpr double kTwoPi = 2.0 * std::numbers::pi;

/// Position inside the period from N shifted samples (the N-step phase-shift formula):
/// phi = atan2(sum I_n sin(2 pi n / N), sum I_n cos(2 pi n / N)). Returns the amplitude.
float wrapped_position(std::span<const cv::Mat> images, int first, int steps, int x, int y,
                       int period_px, float& position) {
    double s = 0.0, c = 0.0;
    for (int n = 0; n < steps; ++n) {
        const double v = images[first + n].at<std::uint8_t>(y, x);
        s += v * std::sin(kTwoPi * n / steps);
        c += v * std::cos(kTwoPi * n / steps);
    }
    double phi = std::atan2(s, c);
    if (phi < 0.0) phi += kTwoPi;
    position = float(phi / kTwoPi * period_px);
    return float(2.0 / steps * std::hypot(s, c));
}

/// Unwrapped coordinate nearest to the Gray-code coordinate, or NaN.
float unwrap(float gray_px, float wrapped_px, float amplitude, const PhaseShiftLayout& phase,
             const PhaseShiftDecodeConfig& config) {
    constexpr float kNaN = std::numeric_limits<float>::quiet_NaN();
    if (std::isnan(gray_px) || amplitude < config.min_modulation) return kNaN;
    const float period = float(phase.period_px);
    const float k = std::round((gray_px - wrapped_px) / period);
    const float x = k * period + wrapped_px;
    return std::abs(x - gray_px) <= config.max_gray_disagreement_px ? x : kNaN;
}

}  // namespace

std::vector<cv::Mat> make_phase_shift_patterns(const GrayCodeLayout& layout,
                                               const PhaseShiftLayout& phase) {
    const int w = layout.projector_width_px;
    const int h = layout.projector_height_px;
    std::vector<cv::Mat> patterns;
    for (int axis = 0; axis < 2; ++axis) {
        for (int n = 0; n < phase.steps; ++n) {
            cv::Mat p(h, w, CV_8UC1);
            for (int y = 0; y < h; ++y) {
                for (int x = 0; x < w; ++x) {
                    const double v = axis == 0 ? x : y;
                    const double a = kTwoPi * v / phase.period_px - kTwoPi * n / phase.steps;
                    p.at<std::uint8_t>(y, x) =
                        cv::saturate_cast<std::uint8_t>(127.5 * (1.0 + std::cos(a)));
                }
            }
            patterns.push_back(p);
        }
    }
    return patterns;
}

Expected<void> refine_with_phase_shift(ProjectorMap& map, std::span<const cv::Mat> images,
                                       const PhaseShiftLayout& phase,
                                       const PhaseShiftDecodeConfig& config) {
    if (phase.steps < 3 || phase.period_px < 2)
        return fail(ErrorCode::kInvalidArgument, "phase shift: need >= 3 steps, period >= 2 px");
    if (auto ok = check_image_sequence(images, std::size_t(phase.image_count()), "phase shift");
        !ok)
        return fail(ok.error());
    if (images[0].size() != map.column_px.size())
        return fail(ErrorCode::kInvalidArgument,
                    "phase shift: images differ in size from the Gray code");
    tbb::parallel_for(
        tbb::blocked_range<int>(0, map.column_px.rows, 16), [&](const tbb::blocked_range<int>& r) {
            for (int y = r.begin(); y < r.end(); ++y) {
                float* col = map.column_px.ptr<float>(y);
                float* row = map.row_px.ptr<float>(y);
                std::uint8_t* contrast = map.contrast.ptr<std::uint8_t>(y);
                for (int x = 0; x < map.column_px.cols; ++x) {
                    if (!contrast[x]) continue;
                    float wc = 0.0f, wr = 0.0f;
                    const float ac =
                        wrapped_position(images, 0, phase.steps, x, y, phase.period_px, wc);
                    const float ar = wrapped_position(images, phase.steps, phase.steps, x, y,
                                                      phase.period_px, wr);
                    col[x] = unwrap(col[x], wc, ac, phase, config);
                    row[x] = unwrap(row[x], wr, ar, phase, config);
                    if (std::isnan(col[x]) || std::isnan(row[x])) {
                        col[x] = row[x] = std::numeric_limits<float>::quiet_NaN();
                        contrast[x] = 0;
                    }
                }
            }
        });
    map.valid_count = std::size_t(cv::countNonZero(map.contrast));
    return {};
}

}  // namespace anascan::drivers::sl
