#include "anascan/processing/normals.hpp"

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include <Eigen/Eigenvalues>
#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>

namespace anascan {
namespace {

enum class Fit : std::uint8_t { kOk, kTooFew, kDegenerate };

struct LocalFit {
    Eigen::Vector3f normal = Eigen::Vector3f::Zero();
    float curvature = 0.0f;
    Fit fit = Fit::kTooFew;
};

// Covariance of the point and its neighbours about their centroid. Coordinates are taken
// relative to the point itself first, so that large offsets from the origin cost no bits
// and float sums suffice (a neighbourhood spans millimetres: its products are far above
// float's rounding of them); the moments are then combined in double.
Eigen::Matrix3d neighbourhood_covariance(std::span<const Eigen::Vector3f> positions, std::size_t i,
                                         std::span<const std::uint32_t> nbrs) {
    const Eigen::Vector3f p0 = positions[i];
    float sx = 0, sy = 0, sz = 0, sxx = 0, sxy = 0, sxz = 0, syy = 0, syz = 0, szz = 0;
    for (const std::uint32_t j : nbrs) {  // The six distinct products only.
        const float x = positions[j].x() - p0.x(), y = positions[j].y() - p0.y(),
                    z = positions[j].z() - p0.z();
        sx += x;
        sy += y;
        sz += z;
        sxx += x * x;
        sxy += x * y;
        sxz += x * z;
        syy += y * y;
        syz += y * z;
        szz += z * z;
    }
    const double n = double(nbrs.size() + 1);  // The point itself adds d = 0.
    const double mx = sx / n, my = sy / n, mz = sz / n;
    Eigen::Matrix3d cov;
    cov(0, 0) = sxx / n - mx * mx;
    cov(1, 1) = syy / n - my * my;
    cov(2, 2) = szz / n - mz * mz;
    cov(0, 1) = cov(1, 0) = sxy / n - mx * my;
    cov(0, 2) = cov(2, 0) = sxz / n - mx * mz;
    cov(1, 2) = cov(2, 1) = syz / n - my * mz;
    return cov;
}

// The smallest eigenvalue of a symmetric positive semi-definite 3x3 matrix by Newton's
// method on its characteristic cubic from 0 (left of the smallest root the cubic rises
// and is concave, so the iterates climb to it without overshooting), and its unit
// eigenvector as the longest cross product of two rows of a - lambda I. False where that
// is ill-conditioned (the two smallest eigenvalues nearly equal), for the general solver.
bool smallest_eigenpair(const Eigen::Matrix3d& a, double& lambda, Eigen::Vector3d& vector) {
    constexpr double kMinGapProduct = 1e-8;  // (λ1 - λ0)(λ2 - λ0) at unit trace.
    constexpr int kMaxIterations = 16;
    const double c2 = a.trace();
    const double c1 = a(0, 0) * a(1, 1) - a(0, 1) * a(0, 1) + a(0, 0) * a(2, 2) -
                      a(0, 2) * a(0, 2) + a(1, 1) * a(2, 2) - a(1, 2) * a(1, 2);
    const double c0 = a.determinant();
    if (!(c1 > 0.0)) return false;
    double x = c0 / c1;  // The first step from 0.
    for (int iteration = 0; iteration < kMaxIterations; ++iteration) {
        const double slope = (3.0 * x - 2.0 * c2) * x + c1;
        if (!(slope > 0.0)) return false;
        const double step = (((x - c2) * x + c1) * x - c0) / slope;
        x -= step;
        if (std::abs(step) <= 1e-13 * c2) break;
    }
    lambda = x;
    const Eigen::Matrix3d m = a - lambda * Eigen::Matrix3d::Identity();
    const std::array<Eigen::Vector3d, 3> candidates = {
        m.row(0).cross(m.row(1)), m.row(0).cross(m.row(2)), m.row(1).cross(m.row(2))};
    std::size_t best = 0;
    for (std::size_t c = 1; c < 3; ++c) {
        if (candidates[c].squaredNorm() > candidates[best].squaredNorm()) best = c;
    }
    const double norm_sq = candidates[best].squaredNorm();
    if (!(norm_sq > kMinGapProduct * kMinGapProduct)) return false;
    vector = candidates[best] / std::sqrt(norm_sq);
    return true;
}

// Local PCA: the normal is the eigenvector of the smallest eigenvalue.
LocalFit fit_point(std::span<const Eigen::Vector3f> positions, std::size_t i,
                   std::span<const std::uint32_t> nbrs, std::size_t min_neighbors) {
    LocalFit out;
    if (nbrs.size() < min_neighbors) return out;
    const Eigen::Matrix3d cov = neighbourhood_covariance(positions, i, nbrs);
    const double trace = cov.trace();
    if (!(trace > 0.0) || !std::isfinite(trace)) {
        out.fit = Fit::kDegenerate;
        return out;
    }
    const Eigen::Matrix3d unit = cov * (1.0 / trace);  // Unit trace: scale-free thresholds.
    double lambda = 0.0;
    Eigen::Vector3d normal;
    if (!smallest_eigenpair(unit, lambda, normal)) {
        Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> solver;
        solver.computeDirect(unit);
        normal = solver.eigenvectors().col(0);
        lambda = solver.eigenvalues()(0);
        if (!normal.allFinite() || normal.squaredNorm() < 0.5) {
            out.fit = Fit::kDegenerate;
            return out;
        }
        normal.normalize();
    }
    out.normal = normal.cast<float>();
    out.curvature = float(std::clamp(lambda, 0.0, 1.0));  // λ0 / Σλ.
    out.fit = Fit::kOk;
    return out;
}

}  // namespace

NormalEstimationResult estimate_normals(PointCloud& cloud, const NormalEstimationConfig& config) {
    NormalEstimationResult result;
    if (cloud.empty()) {
        result.status = NormalStatus::kEmptyCloud;
        cloud.normals.clear();
        return result;
    }
    // Points the neighbour search never reaches (non-finite) keep kTooFew and a zero normal.
    std::vector<Eigen::Vector3f> old;
    if (cloud.normals.size() == cloud.size()) old = std::move(cloud.normals);
    cloud.normals.assign(cloud.size(), Eigen::Vector3f::Zero());
    result.curvature.assign(cloud.size(), 0.0f);
    std::vector<Fit> fits(cloud.size(), Fit::kTooFew);
    const std::size_t min_neighbors = std::size_t(std::max(config.min_neighbors, 2));
    const auto fit = [&](std::size_t i, std::span<const std::uint32_t> neighbors) {
        const LocalFit local = fit_point(cloud.positions, i, neighbors, min_neighbors);
        const bool flip = !old.empty() && local.normal.dot(old[i]) < 0.0f;
        cloud.normals[i] = flip ? Eigen::Vector3f(-local.normal) : local.normal;
        result.curvature[i] = local.curvature;
        fits[i] = local.fit;
    };
    const NeighborGraphConfig search{.k_neighbors = config.k_neighbors,
                                     .max_radius_m = config.max_radius_m};
    if (config.keep_graph) {
        result.graph = build_neighbor_graph(cloud.positions, search);
        tbb::parallel_for(tbb::blocked_range<std::size_t>(0, cloud.size(), 1024),
                          [&](const auto& r) {
                              for (std::size_t i = r.begin(); i < r.end(); ++i) {
                                  fit(i, result.graph.neighbors(i));
                              }
                          });
    } else {
        visit_neighbor_rows(cloud.positions, search,
                            [&](std::size_t i, std::span<const std::uint32_t> neighbors,
                                std::span<const float>) { fit(i, neighbors); });
    }
    for (const Fit f : fits) {
        result.num_estimated += f == Fit::kOk;
        result.num_too_few_neighbors += f == Fit::kTooFew;
        result.num_degenerate += f == Fit::kDegenerate;
    }
    return result;
}

OrientationResult orient_toward(PointCloud& cloud, const Eigen::Vector3f& sensor_origin_m) {
    OrientationResult result;
    if (cloud.normals.size() != cloud.size()) return result;
    std::vector<std::uint8_t> flipped(cloud.size(), 0);
    tbb::parallel_for(tbb::blocked_range<std::size_t>(0, cloud.size(), 4096), [&](const auto& r) {
        for (std::size_t i = r.begin(); i < r.end(); ++i) {
            Eigen::Vector3f& n = cloud.normals[i];
            if (n.dot(sensor_origin_m - cloud.positions[i]) < 0.0f) {
                n = -n;
                flipped[i] = 1;
            }
        }
    });
    for (std::size_t i = 0; i < cloud.size(); ++i) {
        result.num_flipped += flipped[i];
        result.num_unoriented += cloud.normals[i].isZero();
    }
    return result;
}

OrientationResult orient_consistently(PointCloud& cloud,
                                      const ConsistentOrientationConfig& config) {
    const NeighborGraph graph =
        build_neighbor_graph(cloud.positions, {.k_neighbors = config.k_neighbors});
    return orient_consistently(cloud, graph);
}

}  // namespace anascan
