// LiveRegistrar: the reduced, stone-only copy of a new scan.
#include <algorithm>
#include <cmath>
#include <string>

#include "anascan/processing/core/stopwatch.hpp"
#include "anascan/processing/registration/batch/scan_registration.hpp"
#include "anascan/processing/spatial/voxel_grid.hpp"
#include "live/state.hpp"

namespace anascan::acquisition::live {
namespace {

/// The plane turned so that the sensor lies on its positive side.
Plane facing(Plane plane, const Eigen::Vector3f& sensor_local) {
    if (plane.signed_distance_m(sensor_local) < 0.0) {
        plane.normal = -plane.normal;
        plane.offset_m = -plane.offset_m;
    }
    return plane;
}

/// Fraction of the points farther than `band_m` from the plane that lie on its positive side.
double positive_side_fraction(const PointCloud& cloud, const Plane& plane, double band_m) {
    std::size_t positive = 0, off = 0;
    for (const Eigen::Vector3f& p : cloud.positions) {
        const double d = plane.signed_distance_m(p);
        if (std::abs(d) <= band_m) continue;
        ++off;
        positive += d > 0.0;
    }
    return off == 0 ? 0.0 : static_cast<double>(positive) / static_cast<double>(off);
}

/// The ground: among the dominant planes (each rejected one set aside for the next search),
/// the first with the other points on the sensor's side. Empty when none is.
std::optional<Plane> find_ground(const PointCloud& cloud, const Eigen::Vector3f& sensor_local,
                                 const LiveRegistrationConfig& config) {
    PointCloud rest = cloud;
    for (int attempt = 0; attempt < config.prepare.ground_attempts && rest.size() >= 3; ++attempt) {
        const PlaneFitResult fit = find_dominant_plane(rest, config.prepare.ground);
        if (fit.status != PlaneFitStatus::kOk) return std::nullopt;
        const Plane plane = facing(fit.plane, sensor_local);
        if (positive_side_fraction(cloud, plane, config.prepare.ground_band_m) >=
            config.prepare.ground_sensor_side_fraction) {
            return plane;
        }
        std::vector<bool> inlier(rest.size(), false);
        for (std::size_t i : fit.inlier_indices) inlier[i] = true;
        std::vector<std::size_t> keep;
        for (std::size_t i = 0; i < rest.size(); ++i) {
            if (!inlier[i]) keep.push_back(i);
        }
        rest = select(rest, keep);
    }
    return std::nullopt;
}

/// Drops the ground and everything below it (the stone stands on the sensor's side).
void remove_ground(PointCloud& cloud, const Eigen::Vector3f& sensor_local,
                   const LiveRegistrationConfig& config) {
    const std::optional<Plane> ground = find_ground(cloud, sensor_local, config);
    if (!ground) return;
    std::vector<std::size_t> keep;
    keep.reserve(cloud.size());
    for (std::size_t i = 0; i < cloud.size(); ++i) {
        if (ground->signed_distance_m(cloud.positions[i]) > config.prepare.ground_band_m)
            keep.push_back(i);
    }
    cloud = select(cloud, keep);
}

/// Centroid (cloud frame) and the radius of the sphere around it holding every point.
void bounding_sphere(ScanEntry& entry) {
    Eigen::Vector3d sum = Eigen::Vector3d::Zero();
    for (const Eigen::Vector3f& p : entry.cloud.positions) sum += p.cast<double>();
    const Eigen::Vector3d local = sum / static_cast<double>(entry.cloud.size());
    double radius_sq = 0.0;
    for (const Eigen::Vector3f& p : entry.cloud.positions) {
        radius_sq = std::max(radius_sq, (p.cast<double>() - local).squaredNorm());
    }
    entry.centroid_m = entry.cloud.origin_m + local;
    entry.radius_m = std::sqrt(radius_sq);
}

}  // namespace

Prepared prepare_scan(LiveScanInput input, const LiveRegistrationConfig& config) {
    Prepared out;
    ScanEntry& entry = out.entry;
    entry.seq = input.seq;
    entry.sensor_origin_m = input.sensor_origin_scan_m.value_or(Eigen::Vector3d::Zero());
    const std::size_t loaded = input.cloud.size();
    remove_non_finite(input.cloud);
    if (input.cloud.empty()) {
        out.problem = loaded == 0 ? "empty scan (no points)"
                                  : "all " + std::to_string(loaded) + " points are non-finite";
        return out;
    }
    // The copy is kept for the whole capture: positions and normals only (registration
    // reads nothing else), with no spare capacity.
    input.cloud.normals.clear();
    input.cloud.colors.clear();
    input.cloud.intensity.clear();
    input.cloud.confidence.clear();
    entry.cloud = voxel_downsample(input.cloud, {.voxel_size_m = config.prepare.voxel_size_m});
    // Normals on the reduced cloud (batch registration's preparation, without its
    // down-sampling).
    anascan::prepare_scan(entry.cloud, entry.sensor_origin_m,
                          ScanRegistrationConfig{.normals = config.prepare.normals});
    const Eigen::Vector3f sensor_local =
        (entry.sensor_origin_m - entry.cloud.origin_m).cast<float>();
    remove_ground(entry.cloud, sensor_local, config);
    if (entry.cloud.size() < config.prepare.min_scan_points) {
        out.problem = "only " + std::to_string(entry.cloud.size()) + " stone points of " +
                      std::to_string(loaded) +
                      " after down-sampling and ground removal (at least " +
                      std::to_string(config.prepare.min_scan_points) + " are needed)";
        return out;
    }
    bounding_sphere(entry);
    entry.cloud.positions.shrink_to_fit();
    entry.cloud.normals.shrink_to_fit();
    return out;
}

std::string rejection(const FineRegistrationResult& fine, const LiveRegistrationConfig& config,
                      const VerificationLimits& limits) {
    if (fine.status != FineRegistrationStatus::kConverged &&
        fine.status != FineRegistrationStatus::kMaxIterations) {
        return "fine registration: " + std::string(to_string(fine.status));
    }
    if (fine.degeneracy.eigenvalue_ratio <
        std::max(config.hypotheses.fine.degeneracy_threshold, config.verify.min_degeneracy_ratio)) {
        return "degenerate (" + std::to_string(fine.degeneracy.eigenvalue_ratio) + ")";
    }
    if (fine.rms_m > limits.max_rms_m) {
        return "rms too large (limit " + std::to_string(limits.max_rms_m * 1e3) + " mm)";
    }
    if (fine.overlap_fraction < config.verify.min_overlap_fraction) return "overlap too small";
    if (fine.normal_deviation_deg.value_or(0.0) > limits.max_normal_deviation_deg) {
        return "normal deviation too large (" +
               std::to_string(fine.normal_deviation_deg.value_or(0.0)) + " deg)";
    }
    return {};
}

}  // namespace anascan::acquisition::live

namespace anascan::acquisition {

Expected<PointCloud> reduce_to_stone(LiveScanInput scan, const LiveRegistrationConfig& config) {
    live::Prepared prepared = live::prepare_scan(std::move(scan), config);
    if (!prepared.problem.empty()) return fail(ErrorCode::kInvalidArgument, prepared.problem);
    return std::move(prepared.entry.cloud);
}

}  // namespace anascan::acquisition
