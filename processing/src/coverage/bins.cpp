// Coverage, step 1: every scan into the world frame, binned into small voxels whose count
// of captured points is kept, so that density is still measured after down-sampling.

#include <tbb/parallel_for.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <unordered_map>

#include "coverage/steps.hpp"

namespace anascan::coverage_detail {
namespace {

struct Bin {
    Eigen::Vector3d sum = Eigen::Vector3d::Zero();
    double weight = 0.0;
    std::uint32_t count = 0;
};

std::uint64_t bin_key(const Eigen::Vector3d& p, double inv_size) {
    return pack_cell((p * inv_size).array().floor().cast<int>());
}

// One view's bins, in order of first occurrence (deterministic for a given cloud).
struct ViewBins {
    std::vector<Eigen::Vector3f> positions;
    std::vector<float> weights;
};

ViewBins bin_view(const CoverageScanView& view, const Eigen::Vector3d& origin_m,
                  const CoverageConfig& config) {
    const PointCloud& cloud = *view.cloud;
    const Pose T_rel_scan = Eigen::Translation3d(-origin_m) * view.T_world_scan;
    const Eigen::Vector3d shift = T_rel_scan * cloud.origin_m;
    const Eigen::Matrix3d R = T_rel_scan.linear();
    std::unordered_map<std::uint64_t, std::uint32_t> index;
    index.reserve(cloud.size() / 2 + 16);
    std::vector<Bin> bins;
    const double inv_size = 1.0 / config.bin_size_m;
    // Down-sampled first: every step-th point stands for step points.
    const std::size_t step =
        std::max<std::size_t>(1, (cloud.size() + config.max_points_per_view - 1) /
                                     std::max<std::size_t>(1, config.max_points_per_view));
    for (std::size_t i = 0; i < cloud.size(); i += step) {
        const Eigen::Vector3f& local = cloud.positions[i];
        if (!local.allFinite()) continue;
        const Eigen::Vector3d p = shift + R * local.cast<double>();
        auto [it, inserted] =
            index.try_emplace(bin_key(p, inv_size), static_cast<std::uint32_t>(bins.size()));
        if (inserted) bins.emplace_back();
        Bin& bin = bins[it->second];
        bin.sum += p;
        ++bin.count;
    }
    ViewBins out;
    out.positions.reserve(bins.size());
    out.weights.reserve(bins.size());
    for (const Bin& bin : bins) {
        out.positions.push_back((bin.sum / bin.count).cast<float>());
        out.weights.push_back(static_cast<float>(bin.count * step * view.points_per_point));
    }
    return out;
}

Eigen::Vector3d common_origin(std::span<const CoverageScanView> scans) {
    for (const CoverageScanView& view : scans)
        if (view.cloud != nullptr && !view.cloud->empty())
            return view.T_world_scan *
                   (view.cloud->origin_m + view.cloud->positions.front().cast<double>());
    return Eigen::Vector3d::Zero();
}

}  // namespace

BinnedPoints bin_views(std::span<const CoverageScanView> scans, const CoverageConfig& config) {
    BinnedPoints out;
    out.origin_m = common_origin(scans);
    if (!std::isfinite(out.origin_m.sum())) out.origin_m.setZero();
    std::vector<ViewBins> per_view(scans.size());
    tbb::parallel_for(std::size_t{0}, scans.size(), [&](std::size_t v) {
        if (scans[v].cloud != nullptr) per_view[v] = bin_view(scans[v], out.origin_m, config);
    });
    const float nan = std::numeric_limits<float>::quiet_NaN();
    for (std::size_t v = 0; v < scans.size(); ++v) {
        const std::size_t begin = out.positions.size();
        out.positions.insert(out.positions.end(), per_view[v].positions.begin(),
                             per_view[v].positions.end());
        out.weights.insert(out.weights.end(), per_view[v].weights.begin(),
                           per_view[v].weights.end());
        out.views.insert(out.views.end(), per_view[v].positions.size(),
                         static_cast<std::uint32_t>(v));
        out.ranges.emplace_back(begin, out.positions.size());
        const auto& sensor = scans[v].sensor_origin_scan_m;
        out.sensors.push_back(
            sensor ? Eigen::Vector3f((scans[v].T_world_scan * *sensor - out.origin_m).cast<float>())
                   : Eigen::Vector3f::Constant(nan));
    }
    return out;
}

BinnedPoints select_bins(const BinnedPoints& points, std::span<const std::size_t> keep) {
    BinnedPoints out;
    out.origin_m = points.origin_m;
    out.sensors = points.sensors;
    out.ranges.assign(points.ranges.size(), {0, 0});
    std::size_t k = 0;
    for (std::size_t v = 0; v < points.ranges.size(); ++v) {
        out.ranges[v].first = out.positions.size();
        for (; k < keep.size() && keep[k] < points.ranges[v].second; ++k) {
            out.positions.push_back(points.positions[keep[k]]);
            out.weights.push_back(points.weights[keep[k]]);
            out.views.push_back(static_cast<std::uint32_t>(v));
        }
        out.ranges[v].second = out.positions.size();
    }
    return out;
}

}  // namespace anascan::coverage_detail
