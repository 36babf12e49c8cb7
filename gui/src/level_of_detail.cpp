#include "anascan/gui/level_of_detail.hpp"

#include <algorithm>
#include <cmath>
#include <numeric>

namespace anascan::gui {

std::vector<std::size_t> points_to_draw(std::span<const std::size_t> chunk_sizes,
                                        std::size_t budget_points) {
    const std::size_t total =
        std::accumulate(chunk_sizes.begin(), chunk_sizes.end(), std::size_t{0});
    std::vector<std::size_t> counts(chunk_sizes.begin(), chunk_sizes.end());
    if (total <= budget_points) return counts;
    const double fraction = static_cast<double>(budget_points) / static_cast<double>(total);
    for (std::size_t& n : counts) {
        if (n == 0) continue;
        // Floor keeps the sum within the budget; a chunk never vanishes entirely.
        n = std::max<std::size_t>(1, static_cast<std::size_t>(fraction * static_cast<double>(n)));
    }
    return counts;
}

LodController::LodController(LodConfig config)
    : config_(config), budget_(std::max(config.initial_budget_points, config.min_budget_points)) {}

std::size_t LodController::update(double frame_ms, std::size_t total_points) {
    if (!(frame_ms > 0.0)) return budget_;
    const double target = config_.target_frame_ms;
    double next = static_cast<double>(budget_);
    if (frame_ms > target) {
        // Shrink in proportion, but at most halve per frame (one slow frame is noise).
        next *= std::max(0.5, target / frame_ms);
    } else if (frame_ms < 0.6 * target && budget_ < total_points) {
        next *= 1.2;
    }
    budget_ = std::max(config_.min_budget_points, static_cast<std::size_t>(next));
    // Growing beyond what exists only delays the reaction to the next slow frame.
    budget_ = std::min(budget_, std::max(total_points, config_.min_budget_points));
    return budget_;
}

float thinned_point_size_px(float base_px, double fraction_drawn) {
    if (!(fraction_drawn > 0.0) || fraction_drawn >= 1.0) return base_px;
    const double size = base_px / std::sqrt(fraction_drawn);
    return static_cast<float>(std::min(size, 2.0 * base_px));
}

}  // namespace anascan::gui
