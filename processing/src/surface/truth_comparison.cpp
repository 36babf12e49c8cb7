// A fragment model against its true surface (see truth_comparison.hpp).
#include "anascan/processing/surface/truth_comparison.hpp"

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>
#include <vector>

#include "anascan/processing/spatial/triangle_tree.hpp"
#include "anascan/processing/surface/mesh_distance.hpp"

namespace anascan {
namespace {

double quantile(std::vector<double> v, double q) {
    if (v.empty()) return 0.0;
    const auto k = static_cast<std::ptrdiff_t>(q * double(v.size() - 1));
    std::nth_element(v.begin(), v.begin() + k, v.end());
    return v[std::size_t(k)];
}

Eigen::Vector3d box_extent_m(const Mesh& mesh) {
    if (mesh.vertices.empty()) return Eigen::Vector3d::Zero();
    Eigen::Vector3f lo = mesh.vertices.positions.front(), hi = lo;
    for (const Eigen::Vector3f& p : mesh.vertices.positions)
        lo = lo.cwiseMin(p), hi = hi.cwiseMax(p);
    return (hi - lo).cast<double>();
}

bool interpolated(std::span<const SurfaceClass> classes, std::size_t triangle) {
    return !classes.empty() && classes[triangle] == SurfaceClass::kInterpolated;
}

// Distances from each sample to `to`, in parallel.
std::vector<double> distances_to(const std::vector<SurfaceSample>& samples, const Mesh& to) {
    const MeshDistance distance(to);
    std::vector<double> d(samples.size());
    tbb::parallel_for(tbb::blocked_range<std::size_t>(0, samples.size(), 4096), [&](const auto& r) {
        for (std::size_t i = r.begin(); i != r.end(); ++i)
            d[i] = distance.distance_m(samples[i].position_m);
    });
    return d;
}

void accuracy(const Mesh& model, std::span<const SurfaceClass> classes, const Mesh& truth,
              double spacing_m, TruthComparison& out) {
    const std::vector<SurfaceSample> samples = sample_surface(model, spacing_m);
    const std::vector<double> d = distances_to(samples, truth);
    std::vector<double> measured, filled;
    for (std::size_t i = 0; i < samples.size(); ++i)
        (interpolated(classes, samples[i].triangle) ? filled : measured).push_back(d[i]);
    out.measured_samples = measured.size();
    out.interpolated_samples = filled.size();
    out.measured_max_m = measured.empty() ? 0.0 : *std::ranges::max_element(measured);
    out.measured_median_m = quantile(measured, 0.5);
    out.measured_p95_m = quantile(std::move(measured), 0.95);
    out.interpolated_median_m = quantile(filled, 0.5);
    out.interpolated_p95_m = quantile(std::move(filled), 0.95);
}

}  // namespace

TruthComparison compare_with_truth(const Mesh& model, std::span<const SurfaceClass> triangle_class,
                                   const Mesh& truth, const TruthComparisonConfig& config) {
    TruthComparison out;
    out.box_m = box_extent_m(model);
    out.truth_box_m = box_extent_m(truth);
    if (model.triangles.empty() || truth.triangles.empty()) return out;
    accuracy(model, triangle_class, truth, config.model_spacing_m, out);
    const std::vector<SurfaceSample> truth_samples = sample_surface(truth, config.truth_spacing_m);
    const std::vector<double> d = distances_to(truth_samples, model);
    out.truth_samples = d.size();
    const auto near =
        std::ranges::count_if(d, [&](double x) { return x <= config.completeness_within_m; });
    out.completeness = d.empty() ? 0.0 : double(near) / double(d.size());
    return out;
}

}  // namespace anascan
