// Coverage: bin the scans, find the surface (estimated or given), sample it, apply the
// criterion to every sample, group what is missing into holes.

#include "anascan/processing/coverage/coverage.hpp"

#include "coverage/steps.hpp"

namespace anascan {
namespace {

using coverage_detail::BinnedPoints;
using coverage_detail::SurfaceSamples;

constexpr Rgb8 kObservedColor{40, 180, 40};
constexpr Rgb8 kSparseColor{230, 190, 0};
constexpr Rgb8 kUnobservedColor{220, 30, 30};

CoverageReport failed(CoverageStatus status, std::string message) {
    CoverageReport report;
    report.status = status;
    report.message = std::move(message);
    return report;
}

// Samples the surface (relative frame of `points`), classifies, fills the report.
CoverageReport measure(Mesh surface_rel, const BinnedPoints& points, const CoverageConfig& config) {
    const SurfaceSamples samples =
        coverage_detail::sample_surface(surface_rel, config.sample_spacing_m, config.seed);
    if (samples.positions.empty())
        return failed(CoverageStatus::kInvalidSurface, "the surface has no area");
    CoverageReport report;
    report.status = CoverageStatus::kOk;
    report.sample_states = coverage_detail::classify_samples(samples, points, config);
    const double area_per_sample =
        samples.surface_area_m2 / static_cast<double>(samples.positions.size());
    report.surface_area_m2 = samples.surface_area_m2;
    report.samples.origin_m = points.origin_m;
    report.samples.positions = samples.positions;
    report.samples.normals = samples.normals;
    report.samples.colors.reserve(samples.positions.size());
    for (SampleState state : report.sample_states) {
        report.samples.colors.push_back(coverage_sample_color(state));
        if (state == SampleState::kObserved) report.covered_area_m2 += area_per_sample;
        if (state == SampleState::kSparse) report.sparse_area_m2 += area_per_sample;
    }
    report.fraction = report.covered_area_m2 / report.surface_area_m2;
    report.holes =
        coverage_detail::find_holes(samples, report.sample_states, points.origin_m, config);
    surface_rel.vertices.origin_m = points.origin_m;
    report.surface = std::move(surface_rel);
    return report;
}

// Grounds face their view's sensor, i.e. up toward the stone, in the bins' relative frame.
std::optional<Plane> last_ground_world(std::span<const std::optional<Plane>> grounds,
                                       const Eigen::Vector3d& origin_m) {
    for (auto it = grounds.rbegin(); it != grounds.rend(); ++it)
        if (*it)
            return Plane{.normal = (*it)->normal,
                         .offset_m = (*it)->offset_m - (*it)->normal.dot(origin_m)};
    return std::nullopt;
}

bool has_points(std::span<const CoverageScanView> scans) {
    for (const CoverageScanView& view : scans)
        if (view.cloud != nullptr && !view.cloud->empty()) return true;
    return false;
}

}  // namespace

CoverageReport compute_coverage(std::span<const CoverageScanView> scans,
                                const CoverageConfig& config) {
    if (!has_points(scans)) return failed(CoverageStatus::kNoScans, "no scan with points");
    const BinnedPoints all = coverage_detail::bin_views(scans, config);
    const coverage_detail::StoneBins stone = coverage_detail::stone_bins(all, config);
    if (stone.indices.size() < 4)
        return failed(CoverageStatus::kNoStone, "no stone points off the ground");
    const BinnedPoints stone_points = coverage_detail::select_bins(all, stone.indices);
    Mesh hull =
        coverage_detail::convex_hull(coverage_detail::hull_input(stone_points, stone.grounds));
    if (hull.triangles.empty())
        return failed(CoverageStatus::kInvalidSurface, "the stone's points span no volume");
    CoverageReport report = measure(std::move(hull), stone_points, config);
    report.stone_point_count = stone.indices.size();
    report.ground_world = last_ground_world(stone.grounds, all.origin_m);
    return report;
}

CoverageReport compute_coverage_on_surface(const Mesh& surface_world,
                                           std::span<const CoverageScanView> scans,
                                           const CoverageConfig& config) {
    if (!has_points(scans)) return failed(CoverageStatus::kNoScans, "no scan with points");
    const BinnedPoints all = coverage_detail::bin_views(scans, config);
    // The surface in the bins' relative frame (float positions near zero).
    Mesh surface_rel;
    surface_rel.triangles = surface_world.triangles;
    surface_rel.vertices.positions.reserve(surface_world.vertices.size());
    for (std::size_t i = 0; i < surface_world.vertices.size(); ++i)
        surface_rel.vertices.positions.push_back(
            (surface_world.vertices.world_position(i) - all.origin_m).cast<float>());
    return measure(std::move(surface_rel), all, config);
}

Rgb8 coverage_sample_color(SampleState state) {
    switch (state) {
        case SampleState::kObserved:
            return kObservedColor;
        case SampleState::kSparse:
            return kSparseColor;
        case SampleState::kUnobserved:
            break;
    }
    return kUnobservedColor;
}

const char* to_string(CoverageStatus status) {
    switch (status) {
        case CoverageStatus::kOk:
            return "ok";
        case CoverageStatus::kNoScans:
            return "no-scans";
        case CoverageStatus::kNoStone:
            return "no-stone";
        case CoverageStatus::kInvalidSurface:
            return "invalid-surface";
    }
    return "unknown";
}

}  // namespace anascan
