#include "anascan/processing/evaluation/stone_identity.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <numbers>
#include <optional>
#include <vector>

#include "anascan/processing/core/median.hpp"
#include "anascan/processing/features/integral_invariants.hpp"
#include "anascan/processing/spatial/kdtree.hpp"

namespace anascan {
namespace {

/// median |n·(q - p)| of two neighbours with independent normal noise σ is 0.954 σ.
constexpr double kMedianAbsOfDifference = 0.954;
constexpr double kHistogramLow = 0.2, kHistogramHigh = 0.8;
/// A radius takes part in the surface signal when every cloud has this many valid sites.
constexpr std::size_t kMinValidSites = 50;
constexpr std::size_t kMaxWidthPoints = 20000;  ///< Per cloud, for the widths.

using Histograms = std::array<std::vector<double>, kInvariantRadii>;

/// Directions spread evenly over the half sphere z >= 0 (a Fibonacci lattice).
std::vector<Eigen::Vector3d> half_sphere_directions(std::size_t count) {
    std::vector<Eigen::Vector3d> directions;
    const double golden = std::numbers::pi * (3.0 - std::sqrt(5.0));
    for (std::size_t i = 0; i < count; ++i) {
        const double z = (static_cast<double>(i) + 0.5) / static_cast<double>(count);
        const double r = std::sqrt(1.0 - z * z);
        const double phi = golden * static_cast<double>(i);
        directions.emplace_back(r * std::cos(phi), r * std::sin(phi), z);
    }
    return directions;
}

/// Median spacing and point-to-tangent-plane noise, from each sampled point's nearest
/// neighbour.
std::pair<double, double> spacing_and_noise(const PointCloud& cloud, std::size_t max_samples) {
    if (cloud.size() < 2) return {0.0, 0.0};
    const KdTree tree(cloud.positions);
    std::vector<double> spacings, offsets;
    std::vector<Neighbor> nearest;
    const std::size_t stride = std::max<std::size_t>(1, cloud.size() / max_samples);
    for (std::size_t i = 0; i < cloud.size(); i += stride) {
        tree.knn(cloud.positions[i], 2, nearest);
        if (nearest.size() < 2) continue;
        const std::uint32_t j = nearest[1].index;
        spacings.push_back(std::sqrt(static_cast<double>(nearest[1].distance_sq_m2)));
        if (cloud.has_normals() && cloud.normals[i].squaredNorm() > 0.5f)
            offsets.push_back(
                std::abs(cloud.normals[i].dot(cloud.positions[j] - cloud.positions[i])));
    }
    return {upper_median(spacings), upper_median(offsets) / kMedianAbsOfDifference};
}

/// Per radius, the normalised histogram of V_r over the valid sites (empty: too few).
Histograms descriptor_histograms(const PointCloud& cloud, const InvariantRadii& radii,
                                 std::size_t bins) {
    const IntegralInvariantResult ii = compute_integral_invariants(cloud, {.radii_m = radii});
    Histograms out;
    if (ii.status != IntegralInvariantStatus::kOk) return out;
    for (std::size_t k = 0; k < kInvariantRadii; ++k) {
        if (ii.valid_count[k] < kMinValidSites) continue;
        std::vector<double> h(bins, 0.0);
        for (std::size_t s = 0; s < ii.volume.size(); ++s) {
            if (!ii.is_valid(s, k)) continue;
            const double t = (ii.volume[s][k] - kHistogramLow) / (kHistogramHigh - kHistogramLow);
            const auto bin = static_cast<std::size_t>(
                std::clamp(t * static_cast<double>(bins), 0.0, static_cast<double>(bins) - 1.0));
            h[bin] += 1.0 / static_cast<double>(ii.valid_count[k]);
        }
        out[k] = std::move(h);
    }
    return out;
}

/// Mean L1 distance over the radii both have; nullopt when they share none.
std::optional<double> histogram_distance(const Histograms& a, const Histograms& b) {
    double sum = 0.0;
    int radii = 0;
    for (std::size_t k = 0; k < kInvariantRadii; ++k) {
        if (a[k].empty() || b[k].empty()) continue;
        double l1 = 0.0;
        for (std::size_t i = 0; i < a[k].size(); ++i) l1 += std::abs(a[k][i] - b[k][i]);
        sum += l1;
        ++radii;
    }
    if (radii == 0) return std::nullopt;
    return sum / radii;
}

/// The distance from `h` to the nearest of `model` (except `skip`); nullopt when none compares.
std::optional<double> nearest_distance(const Histograms& h, const std::vector<Histograms>& model,
                                       std::size_t skip) {
    std::optional<double> nearest;
    for (std::size_t i = 0; i < model.size(); ++i) {
        if (i == skip) continue;
        const auto d = histogram_distance(h, model[i]);
        if (d && (!nearest || *d < *nearest)) nearest = d;
    }
    return nearest;
}

/// The surface signal: the scan's distance to its nearest model scan, and the model's own
/// spread, the largest distance of a model scan to its nearest other (both -1 when the
/// surface cannot be compared).
void compare_surfaces(std::span<const PointCloud> model_scans, const PointCloud& scan,
                      const StoneIdentityConfig& config, StoneIdentityEvidence& out) {
    if (model_scans.size() < config.min_surface_reference_scans || !(out.spacing_m > 0.0)) return;
    const InvariantRadii radii = radii_for_sample_spacing_m(out.spacing_m);
    std::vector<Histograms> model;
    for (const PointCloud& cloud : model_scans)
        model.push_back(descriptor_histograms(cloud, radii, config.histogram_bins));
    double spread = 0.0;
    for (std::size_t i = 0; i < model.size(); ++i) {
        const auto d = nearest_distance(model[i], model, i);
        if (d) spread = std::max(spread, *d);
    }
    const Histograms mine = descriptor_histograms(scan, radii, config.histogram_bins);
    const auto distance = nearest_distance(mine, model, model.size());
    if (!distance || !(spread > 0.0)) return;
    out.surface_distance = *distance;
    out.surface_spread = spread;
}

/// How much one view of the stone can be wider than the rest of the model: the largest
/// excess of a model scan's width over the width of the other model scans together
/// (-1 with fewer than two scans).
double view_excess_m(const std::vector<const PointCloud*>& model,
                     const StoneIdentityConfig& config) {
    if (model.size() < 2) return -1.0;
    double excess = 0.0;
    for (std::size_t i = 0; i < model.size(); ++i) {
        std::vector<const PointCloud*> others;
        for (std::size_t j = 0; j < model.size(); ++j)
            if (j != i) others.push_back(model[j]);
        const PointCloud* one[] = {model[i]};
        excess = std::max(excess, widest_width_m(one, config) - widest_width_m(others, config));
    }
    return excess;
}

double surface_limit(const StoneIdentityEvidence& e, const StoneIdentityConfig& config) {
    return std::max(config.surface_spread_factor * e.surface_spread, config.min_surface_distance);
}

std::string describe(const StoneIdentityEvidence& e, const StoneIdentityConfig& config) {
    char text[200];
    std::snprintf(text, sizeof(text),
                  "scan %.3f m across, stone's model %.3f m (+%.1f mm for spacing %.1f mm, noise "
                  "%.2f mm",
                  e.scan_width_m, e.model_width_m, e.width_tolerance_m * 1e3, e.spacing_m * 1e3,
                  e.noise_m * 1e3);
    std::string out = text;
    if (e.view_excess_m >= 0.0) {
        std::snprintf(text, sizeof(text),
                      ", one view's excess %.1f mm; model %.1f mm wider than its widest view",
                      e.view_excess_m * 1e3, e.model_growth_m * 1e3);
        out += text;
    }
    out += ")";
    if (e.surface_distance >= 0.0) {
        std::snprintf(text, sizeof(text),
                      "; surface histogram distance %.3f, the model's own spread %.3f (limit %.3f)",
                      e.surface_distance, e.surface_spread, surface_limit(e, config));
        out += text;
    }
    return out;
}

}  // namespace

const char* to_string(StoneIdentityVerdict verdict) {
    switch (verdict) {
        case StoneIdentityVerdict::kOtherStone:
            return "other-stone";
        case StoneIdentityVerdict::kLooksSame:
            return "looks-same";
        case StoneIdentityVerdict::kUndecided:
            return "undecided";
    }
    return "undecided";
}

double widest_width_m(std::span<const PointCloud* const> clouds,
                      const StoneIdentityConfig& config) {
    const std::vector<Eigen::Vector3d> directions = half_sphere_directions(config.width_directions);
    std::vector<double> low(directions.size(), INFINITY), high(directions.size(), -INFINITY);
    for (const PointCloud* cloud : clouds) {
        if (cloud->empty()) continue;
        // Each cloud's own quantiles: a corner that one scan alone saw stays in the width.
        const std::size_t stride = std::max<std::size_t>(1, cloud->size() / kMaxWidthPoints);
        std::vector<Eigen::Vector3d> points;
        for (std::size_t i = 0; i < cloud->size(); i += stride)
            points.push_back(cloud->world_position(i));
        std::vector<double> projections(points.size());
        const auto lo = static_cast<std::ptrdiff_t>(config.width_quantile * points.size());
        const auto hi = static_cast<std::ptrdiff_t>(points.size()) - 1 - lo;
        for (std::size_t d = 0; d < directions.size(); ++d) {
            for (std::size_t i = 0; i < points.size(); ++i)
                projections[i] = directions[d].dot(points[i]);
            std::nth_element(projections.begin(), projections.begin() + lo, projections.end());
            low[d] = std::min(low[d], projections[static_cast<std::size_t>(lo)]);
            std::nth_element(projections.begin(), projections.begin() + hi, projections.end());
            high[d] = std::max(high[d], projections[static_cast<std::size_t>(hi)]);
        }
    }
    double widest = 0.0;
    for (std::size_t d = 0; d < directions.size(); ++d)
        if (high[d] > low[d]) widest = std::max(widest, high[d] - low[d]);
    return widest;
}

StoneIdentityEvidence compare_with_stone(std::span<const PointCloud> model_scans,
                                         const PointCloud& scan,
                                         const StoneIdentityConfig& config) {
    StoneIdentityEvidence out;
    if (model_scans.empty() || scan.size() < 2) {
        out.reason = "nothing to compare (no model or an empty scan)";
        return out;
    }
    std::vector<const PointCloud*> model;
    for (const PointCloud& c : model_scans) {
        model.push_back(&c);
        const auto [spacing, noise] = spacing_and_noise(c, config.max_samples);
        out.spacing_m = std::max(out.spacing_m, spacing);
        out.noise_m = std::max(out.noise_m, noise);
    }
    const auto [spacing, noise] = spacing_and_noise(scan, config.max_samples);
    out.spacing_m = std::max(out.spacing_m, spacing);
    out.noise_m = std::max(out.noise_m, noise);
    out.model_width_m = widest_width_m(model, config);
    const PointCloud* mine[] = {&scan};
    out.scan_width_m = widest_width_m(mine, config);
    out.view_excess_m = view_excess_m(model, config);
    const double noise_tolerance_m = config.width_noise_factor * (out.spacing_m + out.noise_m);
    out.width_tolerance_m = noise_tolerance_m + std::max(0.0, out.view_excess_m);
    compare_surfaces(model_scans, scan, config, out);
    // The size bounds the stone only once the model shows more than one view's worth of it
    // (near-duplicate views leave the rest of the stone unmeasured).
    double widest_view_m = 0.0;
    for (const PointCloud* c : model) {
        const PointCloud* one[] = {c};
        widest_view_m = std::max(widest_view_m, widest_width_m(one, config));
    }
    out.model_growth_m = out.model_width_m - widest_view_m;
    const bool width_known =
        model.size() >= config.min_width_reference_scans && out.model_growth_m > noise_tolerance_m;
    const bool wider = width_known && out.scan_width_m > out.model_width_m + out.width_tolerance_m;
    const bool surface_known = out.surface_distance >= 0.0;
    const bool other_surface = surface_known && out.surface_distance > surface_limit(out, config);
    out.verdict = wider || other_surface         ? StoneIdentityVerdict::kOtherStone
                  : surface_known && width_known ? StoneIdentityVerdict::kLooksSame
                                                 : StoneIdentityVerdict::kUndecided;
    out.reason = describe(out, config);
    return out;
}

}  // namespace anascan
