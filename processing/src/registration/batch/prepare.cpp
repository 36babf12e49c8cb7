// The prepare stage of register_scans: load once, clean, normals, reasons for unusable scans.
#include <cmath>
#include <cstdint>
#include <cstring>
#include <string>
#include <utility>

#include "anascan/processing/cleaning/view_side.hpp"
#include "anascan/processing/features/integral_invariants.hpp"
#include "anascan/processing/spatial/voxel_grid.hpp"
#include "registration/batch/steps.hpp"

namespace anascan {
namespace {

/// Keeps the points whose normal is finite and of unit length (zero = not estimated).
void drop_points_without_normal(PointCloud& cloud) {
    std::vector<std::size_t> keep;
    keep.reserve(cloud.size());
    for (std::size_t i = 0; i < cloud.size(); ++i) {
        const Eigen::Vector3f& n = cloud.normals[i];
        if (n.allFinite() && std::abs(n.squaredNorm() - 1.0f) < 1e-3f) keep.push_back(i);
    }
    if (keep.size() != cloud.size()) cloud = select(cloud, keep);
}

/// Why a loaded cloud of `loaded_count` points cannot be used after preparation left
/// `prepared_count`; empty when it can.
std::string unusable_reason(std::size_t loaded_count, std::size_t finite_count,
                            std::size_t prepared_count, std::size_t min_points) {
    const std::string loaded = std::to_string(loaded_count);
    if (loaded_count == 0) return "empty scan (no points)";
    if (finite_count == 0) return "all " + loaded + " points are non-finite (NaN or infinite)";
    if (prepared_count == 0) {
        return "no normal could be estimated for any of its " + std::to_string(finite_count) +
               " finite points (duplicate points or too few distinct positions)";
    }
    if (prepared_count < min_points) {
        return "only " + std::to_string(prepared_count) + " usable points of " + loaded +
               " (at least " + std::to_string(min_points) + " are needed for descriptors)";
    }
    return {};
}

bool same_positions(const PointCloud& a, const PointCloud& b) {
    return a.size() == b.size() && a.origin_m == b.origin_m &&
           std::memcmp(a.positions.data(), b.positions.data(),
                       sizeof(Eigen::Vector3f) * a.size()) == 0;
}

}  // namespace

namespace detail {

/// FNV-1a over the origin and local positions: equal clouds give equal hashes.
std::uint64_t position_hash(const PointCloud& cloud) {
    std::uint64_t hash = 1469598103934665603ull;
    const auto mix = [&hash](const void* data, std::size_t bytes) {
        const auto* p = static_cast<const unsigned char*>(data);
        for (std::size_t i = 0; i < bytes; ++i) hash = (hash ^ p[i]) * 1099511628211ull;
    };
    mix(cloud.origin_m.data(), sizeof(double) * 3);
    mix(cloud.positions.data(), sizeof(Eigen::Vector3f) * cloud.positions.size());
    return hash;
}

// Bounding sphere, diagonal and hash of a prepared cloud (points set by the caller).
detail::ScanSummary summarize(const PointCloud& cloud) {
    const Bounds bounds = local_bounds(cloud);
    return {.centre_m = cloud.origin_m + (0.5 * (bounds.min + bounds.max)).cast<double>(),
            .radius_m = 0.5 * static_cast<double>(bounds.extent().norm()),
            .diagonal_m = static_cast<double>(bounds.extent().norm()),
            .position_hash = position_hash(cloud)};
}

}  // namespace detail

std::size_t prepare_scan(PointCloud& cloud, const std::optional<Eigen::Vector3d>& sensor_origin_m,
                         const ScanRegistrationConfig& config) {
    remove_non_finite(cloud);
    if (cloud.empty()) return 0;
    if (!cloud.has_normals()) {
        estimate_normals(cloud, config.normals);
        if (sensor_origin_m) {
            orient_toward(cloud, (*sensor_origin_m - cloud.origin_m).cast<float>());
        } else {
            orient_as_range_scan(cloud, config.view_side);
        }
    }
    drop_points_without_normal(cloud);
    if (config.voxel_size_m > 0.0 && !cloud.empty()) {
        cloud = voxel_downsample(cloud, {.voxel_size_m = config.voxel_size_m});
    }
    return cloud.size();
}

namespace detail {

PreparedScans load_and_prepare(const std::vector<ScanInput>& inputs,
                               const ScanRegistrationConfig& config,
                               const RegistrationProgress& progress,
                               ScanRegistrationResult& result) {
    PreparedScans prepared{.store = CloudStore({.directory = config.spill_directory,
                                                .max_loaded = config.max_loaded_clouds}),
                           .summary = std::vector<ScanSummary>(inputs.size()),
                           .spacing_m = std::vector<double>(inputs.size(), 0.0),
                           .viewpoint_m = {},
                           .spill_directory = config.spill_directory};
    for (const ScanInput& input : inputs) {
        prepared.viewpoint_m.push_back(input.sensor_origin_known ? input.sensor_origin_scan_m
                                                                 : std::nullopt);
    }
    for (std::size_t i = 0; i < inputs.size(); ++i) {
        ScanOutcome& scan = result.scans[i];
        if (progress) progress("preparing " + inputs[i].name);
        Expected<PointCloud> loaded =
            inputs[i].load ? inputs[i].load() : Expected<PointCloud>(PointCloud{});
        if (!loaded) {
            scan.reason = "could not be loaded: " + loaded.error().message;
            continue;
        }
        const std::size_t loaded_count = loaded->size();
        const std::size_t finite_count = loaded_count - remove_non_finite(*loaded);
        scan.normals_estimated = !loaded->has_normals();
        scan.point_count = prepare_scan(*loaded, inputs[i].sensor_origin_scan_m, config);
        scan.reason =
            unusable_reason(loaded_count, finite_count, scan.point_count, config.min_scan_points);
        if (!scan.reason.empty()) continue;
        prepared.spacing_m[i] = scan.spacing_m = median_sample_spacing_m(*loaded);
        const std::size_t points = loaded->size();
        ScanSummary summary = summarize(*loaded);
        if (auto put = prepared.store.put(2 * i, std::move(*loaded)); !put) {
            scan.reason = "could not be spilled: " + put.error().message;
            if (prepared.spill_error.empty()) prepared.spill_error = put.error().message;
            continue;
        }
        summary.points = points;
        prepared.summary[i] = summary;
    }
    return prepared;
}

void warn_identical_scans(PreparedScans& scans, ScanRegistrationResult& result) {
    for (std::size_t i = 0; i < scans.size(); ++i) {
        if (!scans.usable(i)) continue;
        for (std::size_t j = 0; j < i; ++j) {
            if (!scans.usable(j) ||
                scans.summary[i].position_hash != scans.summary[j].position_hash ||
                !same_positions(*scans.cloud(i), *scans.cloud(j))) {
                continue;
            }
            result.scans[i].warning = "the same points as " + result.scans[j].name +
                                      " (a copy of one scan adds nothing; check the file list)";
            break;
        }
    }
}

}  // namespace detail
}  // namespace anascan
