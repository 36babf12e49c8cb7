#include "anascan/sim/tof_scanner.hpp"

#include <tbb/parallel_for.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <numbers>

#include "hash_random.hpp"

namespace anascan::sim {
namespace {

constexpr double kDegToRad = std::numbers::pi / 180.0;
constexpr double kMaxRays = 1e8;

struct SweepGrid {
    int rows = 0, cols = 0;
    double step_rad = 0.0, azimuth0_rad = 0.0, elevation0_rad = 0.0;

    // Unit ray of pixel (row, col) in the scanner frame.
    Eigen::Vector3d ray(int row, int col) const {
        const double azimuth = azimuth0_rad + col * step_rad;
        const double elevation = elevation0_rad - row * step_rad;
        return {std::cos(elevation) * std::cos(azimuth), std::cos(elevation) * std::sin(azimuth),
                std::sin(elevation)};
    }
};

Expected<SweepGrid> make_grid(const TofScannerConfig& c) {
    const double step = c.angular_step_deg * kDegToRad;
    if (!(step > 0.0))
        return fail(ErrorCode::kInvalidArgument, "sim:tof: angular step must be > 0 degrees");
    const double span_az = std::min(c.azimuth_span_deg, 360.0) * kDegToRad;
    const double span_el = (c.elevation_max_deg - c.elevation_min_deg) * kDegToRad;
    if (!(span_az > 0.0) || !(span_el >= 0.0) || std::abs(c.elevation_max_deg) > 90.0 ||
        std::abs(c.elevation_min_deg) > 90.0)
        return fail(ErrorCode::kInvalidArgument, "sim:tof: empty or invalid angular window");
    // A full circle has no duplicate last column.
    const bool full = c.azimuth_span_deg >= 360.0;
    const double cols = full ? std::round(span_az / step) : std::floor(span_az / step + 1e-9) + 1;
    const double rows = std::floor(span_el / step + 1e-9) + 1;
    if (cols * rows > kMaxRays)
        return fail(ErrorCode::kInvalidArgument, "sim:tof: more than 1e8 rays; use a coarser step");
    return SweepGrid{.rows = static_cast<int>(rows),
                     .cols = static_cast<int>(cols),
                     .step_rad = step,
                     .azimuth0_rad = c.azimuth_start_deg * kDegToRad,
                     .elevation0_rad = c.elevation_max_deg * kDegToRad};
}

// True range and reflected intensity per pixel (NaN range: no return).
struct RangeImage {
    std::vector<double> range_m;
    std::vector<float> intensity;
};

Expected<RangeImage> cast_sweep(const RayCaster& caster,
                                const std::vector<float>& albedo_of_triangle,
                                const Pose& T_world_scanner, const SweepGrid& grid,
                                const TofSweepControl& control) {
    RangeImage image{std::vector<double>(std::size_t(grid.rows) * grid.cols, NAN),
                     std::vector<float>(std::size_t(grid.rows) * grid.cols, 0.0f)};
    // Blocks of rows, so that a caller can follow and stop the sweep between them.
    const int rows_per_block = std::max(1, grid.rows / 20);
    for (int first = 0; first < grid.rows; first += rows_per_block) {
        if (control.keep_going && !control.keep_going(double(first) / grid.rows))
            return fail(ErrorCode::kCancelled, "sim:tof: sweep stopped");
        const int last = std::min(grid.rows, first + rows_per_block);
        tbb::parallel_for(first, last, [&](int row) {
            for (int col = 0; col < grid.cols; ++col) {
                const Eigen::Vector3d dir = T_world_scanner.linear() * grid.ray(row, col);
                const auto hit = caster.cast(T_world_scanner.translation(), dir);
                if (!hit) continue;
                const std::size_t i = std::size_t(row) * grid.cols + col;
                const double albedo =
                    albedo_of_triangle.empty() ? 0.5 : albedo_of_triangle[hit->triangle];
                image.range_m[i] = hit->distance_m;
                image.intensity[i] = static_cast<float>(albedo * std::abs(hit->normal.dot(dir)));
            }
        });
    }
    return image;
}

// Range of the surface across a depth edge at pixel (row, col), or NaN: along each grid
// direction the range's second difference exceeds the jump where the surface breaks (a
// smooth slanted surface has a small one); the far side is the neighbour farther away.
double across_edge_range(const TofScannerConfig& c, const SweepGrid& grid, const RangeImage& image,
                         int row, int col) {
    auto range_at = [&](int r, int k) {
        if (r < 0 || r >= grid.rows) return static_cast<double>(NAN);
        return image.range_m[std::size_t(r) * grid.cols + (k + grid.cols) % grid.cols];
    };
    const double r0 = range_at(row, col);
    double other = NAN, best_jump = c.mixed_pixel_jump_m;
    const std::array<std::array<int, 2>, 2> axes{{{1, 0}, {0, 1}}};
    for (const auto& [dr, dc] : axes) {
        const double before = range_at(row - dr, col - dc), after = range_at(row + dr, col + dc);
        if (!std::isfinite(before) || !std::isfinite(after)) continue;
        const double jump = std::abs(after - 2.0 * r0 + before);
        if (jump <= best_jump) continue;
        best_jump = jump;
        other = std::abs(after - r0) > std::abs(before - r0) ? after : before;
    }
    return other;
}

// The measured range of pixel (row, col): at a depth edge, with the configured
// probability, a mixed pixel uniformly between the two surfaces; plus Gaussian noise.
double measured_range(const TofScannerConfig& c, const SweepGrid& grid, const RangeImage& image,
                      int row, int col, bool& mixed) {
    const std::size_t i = std::size_t(row) * grid.cols + col;
    const double r = image.range_m[i];
    const std::uint64_t h = detail::hash3(c.seed, i);
    const double other = across_edge_range(c, grid, image, row, col);
    mixed = std::isfinite(other) &&
            detail::unit_from_hash(detail::mix64(h + 1)) < c.mixed_pixel_probability;
    const double mixed_r =
        mixed ? r + detail::unit_from_hash(detail::mix64(h + 2)) * (other - r) : r;
    return mixed_r + c.range_noise_sigma_m * detail::normal_from_hash(h);
}

ScanMetadata tof_metadata(const TofScannerConfig& c, const Pose& T_world_scanner) {
    ScanMetadata meta;
    meta.id = c.scan_id;
    meta.sequence = 0;
    meta.device_id = c.device_id;
    meta.device_kind = DeviceKind::kTimeOfFlight;
    meta.sensor_origin_scan_m = Eigen::Vector3d::Zero();
    meta.T_world_scan = T_world_scanner;
    char json[256];
    std::snprintf(json, sizeof(json),
                  "{\"angular_step_deg\": %g, \"range_noise_sigma_m\": %g, \"min_range_m\": %g, "
                  "\"max_range_m\": %g, \"seed\": %llu}",
                  c.angular_step_deg, c.range_noise_sigma_m, c.min_range_m, c.max_range_m,
                  static_cast<unsigned long long>(c.seed));
    meta.settings_json = json;
    return meta;
}

}  // namespace

Expected<TofScanResult> simulate_tof_scan(const RayCaster& caster,
                                          const std::vector<float>& albedo_of_triangle,
                                          const Pose& T_world_scanner,
                                          const TofScannerConfig& config,
                                          const TofSweepControl& control) {
    auto grid = make_grid(config);
    if (!grid) return fail(grid.error());
    auto swept = cast_sweep(caster, albedo_of_triangle, T_world_scanner, *grid, control);
    if (!swept) return fail(swept.error());
    const RangeImage& image = *swept;
    TofScanResult result;
    result.scan.meta = tof_metadata(config, T_world_scanner);
    result.grid = RangeGrid{
        .rows = grid->rows,
        .cols = grid->cols,
        .point_index = std::vector<std::int32_t>(image.range_m.size(), RangeGrid::kNoSample)};
    PointCloud& cloud = result.scan.cloud;
    for (int row = 0; row < grid->rows; ++row) {
        for (int col = 0; col < grid->cols; ++col) {
            const std::size_t i = std::size_t(row) * grid->cols + col;
            if (!std::isfinite(image.range_m[i])) continue;
            bool mixed = false;
            const double r = measured_range(config, *grid, image, row, col, mixed);
            if (r < config.min_range_m || r > config.max_range_m) continue;
            result.grid.point_index[i] = static_cast<std::int32_t>(cloud.positions.size());
            cloud.positions.push_back((r * grid->ray(row, col)).cast<float>());
            cloud.intensity.push_back(image.intensity[i]);
            result.true_range_m.push_back(static_cast<float>(image.range_m[i]));
            result.mixed.push_back(mixed ? 1 : 0);
        }
    }
    return result;
}

}  // namespace anascan::sim
