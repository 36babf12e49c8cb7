#pragma once
/// \file
/// Level of detail for the point view. Each chunk's points are uploaded in a random order
/// (fixed seed), so any prefix of a chunk is a uniform sample of it: drawing the first
/// n_i' = ceil(f · n_i) points of every chunk thins the whole model evenly. The fraction f
/// comes from a point budget that a controller adapts to the measured frame time.

#include <cstddef>
#include <span>
#include <vector>

namespace anascan::gui {

/// How many points of each chunk to draw so that their sum stays within `budget_points`
/// (every chunk keeps the same fraction, at least 1 point of a non-empty chunk).
std::vector<std::size_t> points_to_draw(std::span<const std::size_t> chunk_sizes,
                                        std::size_t budget_points);

struct LodConfig {
    double target_frame_ms = 25.0;           ///< Frame time the budget aims for.
    std::size_t min_budget_points = 25'000;  ///< Still a recognisable stone, enlarged.
    std::size_t initial_budget_points = 300'000;
};

/// Adapts the point budget to the frame time: shrinks it in proportion when a frame is too
/// slow, grows it by 20 % when a frame is clearly fast (under 60 % of the target).
/// Deterministic in its inputs. Not thread-safe.
class LodController {
public:
    explicit LodController(LodConfig config = {});
    /// Feeds the last frame's time (ms) and the points it could have drawn; returns the new
    /// budget.
    std::size_t update(double frame_ms, std::size_t total_points);
    std::size_t budget() const { return budget_; }

private:
    LodConfig config_;
    std::size_t budget_;
};

/// Point size in pixels that fills the gaps left by thinning: base / sqrt(f), at most 2×
/// (a full-density stone has many points per pixel, and with llvmpipe large points cost
/// fill time: 8 px points made turning frames ~25 % slower than 4 px ones).
float thinned_point_size_px(float base_px, double fraction_drawn);

}  // namespace anascan::gui
