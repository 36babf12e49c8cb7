#include "anascan/processing/cleaning/plane_removal.hpp"

#include <tbb/blocked_range.h>
#include <tbb/parallel_reduce.h>

#include <Eigen/Eigenvalues>
#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <functional>
#include <random>

namespace anascan {
namespace {

std::vector<std::size_t> finite_indices(const PointCloud& cloud) {
    std::vector<std::size_t> out;
    out.reserve(cloud.size());
    for (std::size_t i = 0; i < cloud.size(); ++i) {
        if (cloud.positions[i].allFinite()) out.push_back(i);
    }
    return out;
}

// Points of `finite` within the band of `plane` (an integer sum: thread-count independent).
std::size_t count_inliers(const PointCloud& cloud, const std::vector<std::size_t>& finite,
                          const Plane& plane, double threshold_m) {
    return tbb::parallel_reduce(
        tbb::blocked_range<std::size_t>(0, finite.size(), 8192), std::size_t(0),
        [&](const auto& r, std::size_t count) {
            for (std::size_t s = r.begin(); s < r.end(); ++s) {
                count +=
                    std::abs(plane.signed_distance_m(cloud.positions[finite[s]])) <= threshold_m;
            }
            return count;
        },
        std::plus<>());
}

// Plane through three points; false when they are (nearly) collinear.
bool plane_through(const Eigen::Vector3d& a, const Eigen::Vector3d& b, const Eigen::Vector3d& c,
                   Plane& plane) {
    const Eigen::Vector3d n = (b - a).cross(c - a);
    const double scale = (b - a).squaredNorm() * (c - a).squaredNorm();
    if (!(n.squaredNorm() > 1e-12 * scale) || scale == 0.0) return false;
    plane.normal = n.normalized();
    plane.offset_m = -plane.normal.dot(a);
    return true;
}

// Hypotheses needed to draw one all-inlier triple with probability `confidence`.
int needed_iterations(double inlier_fraction, double confidence, int max_iterations) {
    const double all_inliers = std::pow(inlier_fraction, 3.0);
    if (all_inliers >= 1.0) return 1;
    if (all_inliers <= 0.0) return max_iterations;
    const double n = std::log(1.0 - confidence) / std::log(1.0 - all_inliers);
    return int(std::min(double(max_iterations), std::ceil(n)));
}

Plane ransac(const PointCloud& cloud, const std::vector<std::size_t>& finite,
             const PlaneFitConfig& config, int& iterations) {
    std::mt19937_64 rng(config.seed);
    Plane best;
    std::size_t best_count = 0;
    int needed = std::max(config.max_iterations, 1);
    for (iterations = 0; iterations < needed; ++iterations) {
        const std::size_t ia = finite[rng() % finite.size()];
        const std::size_t ib = finite[rng() % finite.size()];
        const std::size_t ic = finite[rng() % finite.size()];
        Plane plane;
        if (!plane_through(cloud.positions[ia].cast<double>(), cloud.positions[ib].cast<double>(),
                           cloud.positions[ic].cast<double>(), plane)) {
            continue;
        }
        const std::size_t count = count_inliers(cloud, finite, plane, config.distance_threshold_m);
        if (count <= best_count) continue;
        best = plane;
        best_count = count;
        const double fraction = double(count) / double(finite.size());
        needed = needed_iterations(fraction, config.confidence, std::max(config.max_iterations, 1));
    }
    return best;
}

std::vector<std::size_t> inliers_of(const PointCloud& cloud, const std::vector<std::size_t>& finite,
                                    const Plane& plane, double threshold_m) {
    std::vector<std::size_t> out;
    for (const std::size_t i : finite) {
        if (std::abs(plane.signed_distance_m(cloud.positions[i])) <= threshold_m) out.push_back(i);
    }
    return out;
}

// Least-squares plane (smallest principal axis about the centroid), in double.
Plane refit(const PointCloud& cloud, const std::vector<std::size_t>& inliers, Plane plane) {
    if (inliers.size() < 3) return plane;
    const Eigen::Vector3d p0 = cloud.positions[inliers.front()].cast<double>();
    Eigen::Vector3d sum = Eigen::Vector3d::Zero();
    Eigen::Matrix3d sum_sq = Eigen::Matrix3d::Zero();
    for (const std::size_t i : inliers) {
        const Eigen::Vector3d d = cloud.positions[i].cast<double>() - p0;
        sum += d;
        sum_sq.noalias() += d * d.transpose();
    }
    const double n = double(inliers.size());
    const Eigen::Vector3d mean = sum / n;
    const Eigen::Matrix3d cov = sum_sq / n - mean * mean.transpose();
    const Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> solver(cov);
    const Eigen::Vector3d normal = solver.eigenvectors().col(0).normalized();
    if (!normal.allFinite()) return plane;
    plane.normal = normal.dot(plane.normal) < 0.0 ? Eigen::Vector3d(-normal) : normal;
    plane.offset_m = -plane.normal.dot(p0 + mean);
    return plane;
}

// Normal toward the side with more off-plane points; +z when there are none.
void orient_plane(const PointCloud& cloud, const std::vector<std::size_t>& finite,
                  double threshold_m, Plane& plane) {
    std::ptrdiff_t balance = 0;
    for (const std::size_t i : finite) {
        const double d = plane.signed_distance_m(cloud.positions[i]);
        if (std::abs(d) > threshold_m) balance += d > 0.0 ? 1 : -1;
    }
    if (balance < 0 || (balance == 0 && plane.normal.z() < 0.0)) {
        plane.normal = -plane.normal;
        plane.offset_m = -plane.offset_m;
    }
}

double rms_distance_m(const PointCloud& cloud, const std::vector<std::size_t>& inliers,
                      const Plane& plane) {
    if (inliers.empty()) return 0.0;
    double sum_sq = 0.0;
    for (const std::size_t i : inliers) {
        const double d = plane.signed_distance_m(cloud.positions[i]);
        sum_sq += d * d;
    }
    return std::sqrt(sum_sq / double(inliers.size()));
}

}  // namespace

PlaneFitResult find_dominant_plane(const PointCloud& cloud, const PlaneFitConfig& config) {
    PlaneFitResult result;
    const std::vector<std::size_t> finite = finite_indices(cloud);
    if (finite.size() < 3) return result;
    const double threshold = config.distance_threshold_m;
    Plane plane = ransac(cloud, finite, config, result.iterations);
    for (int round = 0; round < 2; ++round) {  // Refit, then refit on the new inliers.
        plane = refit(cloud, inliers_of(cloud, finite, plane, threshold), plane);
    }
    orient_plane(cloud, finite, threshold, plane);
    result.plane = plane;
    result.inlier_indices = inliers_of(cloud, finite, plane, threshold);
    result.inlier_fraction = double(result.inlier_indices.size()) / double(finite.size());
    result.rms_m = rms_distance_m(cloud, result.inlier_indices, plane);
    result.status = result.inlier_fraction > config.min_inlier_fraction
                        ? PlaneFitStatus::kOk
                        : PlaneFitStatus::kNoDominantPlane;
    return result;
}

PlaneRemovalResult remove_dominant_plane(const PointCloud& cloud, const PlaneFitConfig& config) {
    PlaneRemovalResult result;
    result.fit = find_dominant_plane(cloud, config);
    const bool remove = result.fit.status == PlaneFitStatus::kOk;
    const std::vector<std::size_t>& inliers = result.fit.inlier_indices;
    std::size_t next = 0;  // Both lists are increasing: one merge pass.
    for (std::size_t i = 0; i < cloud.size(); ++i) {
        const bool is_inlier = next < inliers.size() && inliers[next] == i;
        next += is_inlier;
        if (cloud.positions[i].allFinite() && !(remove && is_inlier)) {
            result.kept_indices.push_back(i);
        }
    }
    return result;
}

}  // namespace anascan
