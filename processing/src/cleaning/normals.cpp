#include "anascan/processing/cleaning/normals.hpp"

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include <Eigen/Eigenvalues>
#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <cstring>

#if defined(__SSE2__)
#include <emmintrin.h>
#endif

#include "cleaning/normals_solve.hpp"

namespace anascan {
namespace {

using normals_detail::CovarianceArrays;
using normals_detail::EigenpairArrays;
using normals_detail::smallest_eigenpair;
using normals_detail::solve_smallest;

enum class Fit : std::uint8_t { kOk, kTooFew, kDegenerate };

struct LocalFit {  // One point's result.
    Eigen::Vector3f normal = Eigen::Vector3f::Zero();
    float curvature = 0.0f;
    Fit fit = Fit::kTooFew;
};

#if defined(__SSE2__)
// (x, y, z, 0), reading only the point's three floats. The first two are copied as one
// 8-byte value: a point is only 4-byte aligned, and dereferencing it as a double (what
// _mm_load_sd does) is undefined behaviour; memcpy compiles to the same single load.
inline __m128 load_xyz(const Eigen::Vector3f& p) {
    double x_and_y = 0.0;
    std::memcpy(&x_and_y, p.data(), sizeof x_and_y);
    const __m128 xy = _mm_castpd_ps(_mm_set_sd(x_and_y));
    return _mm_movelh_ps(xy, _mm_load_ss(p.data() + 2));
}
#endif

// Covariance of the point and its neighbours about their centroid. Coordinates are taken
// relative to the point itself first, so that large offsets from the origin cost no bits
// and float sums suffice (a neighbourhood spans millimetres: its products are far above
// float's rounding of them); the moments are then combined in double.
Eigen::Matrix3d neighbourhood_covariance(std::span<const Eigen::Vector3f> positions, std::size_t i,
                                         std::span<const std::uint32_t> nbrs) {
    const Eigen::Vector3f p0 = positions[i];
    float sx = 0, sy = 0, sz = 0, sxx = 0, sxy = 0, sxz = 0, syy = 0, syz = 0, szz = 0;
#if defined(__SSE2__)
    // The same sums, in the same order, a point per step: (x, y, z), their squares and
    // (xy, yz, zx) in three registers.
    const __m128 origin = load_xyz(p0);
    __m128 sum = _mm_setzero_ps(), squares = sum, products = sum;
    for (const std::uint32_t j : nbrs) {
        const __m128 d = _mm_sub_ps(load_xyz(positions[j]), origin);
        sum = _mm_add_ps(sum, d);
        squares = _mm_add_ps(squares, _mm_mul_ps(d, d));
        products =
            _mm_add_ps(products, _mm_mul_ps(d, _mm_shuffle_ps(d, d, _MM_SHUFFLE(3, 0, 2, 1))));
    }
    alignas(16) float out[3][4];
    _mm_store_ps(out[0], sum);
    _mm_store_ps(out[1], squares);
    _mm_store_ps(out[2], products);
    sx = out[0][0], sy = out[0][1], sz = out[0][2];
    sxx = out[1][0], syy = out[1][1], szz = out[1][2];
    sxy = out[2][0], syz = out[2][1], sxz = out[2][2];
#else
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
#endif
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

// Stores point i's covariance at unit trace (the thresholds are scale-free) for the batch
// solve, or says why it has none.
Fit store_covariance(std::span<const Eigen::Vector3f> positions, std::size_t i,
                     std::span<const std::uint32_t> nbrs, std::size_t min_neighbors,
                     CovarianceArrays& covariances) {
    if (nbrs.size() < min_neighbors) return Fit::kTooFew;
    const Eigen::Matrix3d cov = neighbourhood_covariance(positions, i, nbrs);
    const double trace = cov.trace();
    if (!(trace > 0.0) || !std::isfinite(trace)) return Fit::kDegenerate;
    covariances.set(i, cov * (1.0 / trace));
    return Fit::kOk;
}

// Local PCA: the normal is the eigenvector of the smallest eigenvalue, from the batch solve
// where it settled, else solved alone (Newton, then Eigen's general solver).
LocalFit finish_point(const CovarianceArrays& covariances, std::size_t i,
                      const Eigen::Vector3f& vector, float lambda, bool settled) {
    LocalFit out;
    if (settled) {
        out.normal = vector.normalized();
        out.curvature = std::clamp(lambda, 0.0f, 1.0f);  // λ0 / Σλ.
        out.fit = Fit::kOk;
        return out;
    }
    const Eigen::Matrix3d unit = covariances.get(i);
    double smallest = 0.0;
    Eigen::Vector3d normal;
    if (!smallest_eigenpair(unit, smallest, normal)) {
        Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> solver;
        solver.computeDirect(unit);
        normal = solver.eigenvectors().col(0);
        smallest = solver.eigenvalues()(0);
        if (!normal.allFinite() || normal.squaredNorm() < 0.5) {
            out.fit = Fit::kDegenerate;
            return out;
        }
        normal.normalize();
    }
    out.normal = normal.cast<float>();
    out.curvature = float(std::clamp(smallest, 0.0, 1.0));
    out.fit = Fit::kOk;
    return out;
}

}  // namespace

namespace {

// Each point's neighbourhood covariance, from the k-NN rows as the search finds them (or
// from the kept graph). Points the search never reaches (non-finite) keep kTooFew.
std::vector<Fit> neighbourhood_covariances(const PointCloud& cloud,
                                           const NormalEstimationConfig& config,
                                           CovarianceArrays& covariances,
                                           NormalEstimationResult& result) {
    const std::size_t n = cloud.size();
    std::vector<Fit> fits(n, Fit::kTooFew);
    covariances.resize(n);
    const std::size_t min_neighbors = std::size_t(std::max(config.min_neighbors, 2));
    const auto store = [&](std::size_t i, std::span<const std::uint32_t> neighbors) {
        fits[i] = store_covariance(cloud.positions, i, neighbors, min_neighbors, covariances);
    };
    const NeighborGraphConfig search{.k_neighbors = config.k_neighbors,
                                     .max_radius_m = config.max_radius_m};
    if (config.keep_graph) {
        result.graph = build_neighbor_graph(cloud.positions, search);
        tbb::parallel_for(tbb::blocked_range<std::size_t>(0, n, 1024), [&](const auto& r) {
            for (std::size_t i = r.begin(); i < r.end(); ++i) store(i, result.graph.neighbors(i));
        });
    } else {
        visit_neighbor_rows(cloud.positions, search,
                            [&](std::size_t i, std::span<const std::uint32_t> neighbors,
                                std::span<const float>) { store(i, neighbors); });
    }
    return fits;
}

// The normals and curvatures of the fitted covariances, solved in batches; a normal keeps
// the side of the one the cloud had before, when it had normals.
void solve_normals(const CovarianceArrays& covariances, std::vector<Fit>& fits, PointCloud& cloud,
                   NormalEstimationResult& result) {
    const std::size_t n = cloud.size();
    std::vector<Eigen::Vector3f> old;
    if (cloud.normals.size() == n) old = std::move(cloud.normals);
    cloud.normals.resize(n);  // Every entry is written below.
    result.curvature.resize(n);
    tbb::parallel_for(tbb::blocked_range<std::size_t>(0, n, 1024), [&](const auto& r) {
        const std::size_t m = r.size();
        std::vector<float> x(m), y(m), z(m), lambda(m);
        std::vector<std::uint8_t> settled(m);
        solve_smallest(covariances, r.begin(), r.end(),
                       {x.data(), y.data(), z.data(), lambda.data(), settled.data()});
        for (std::size_t i = r.begin(); i < r.end(); ++i) {
            if (fits[i] != Fit::kOk) {
                cloud.normals[i].setZero();
                result.curvature[i] = 0.0f;
                continue;
            }
            const std::size_t j = i - r.begin();
            const LocalFit local =
                finish_point(covariances, i, {x[j], y[j], z[j]}, lambda[j], settled[j] != 0);
            const bool flip = !old.empty() && local.normal.dot(old[i]) < 0.0f;
            cloud.normals[i] = flip ? Eigen::Vector3f(-local.normal) : local.normal;
            result.curvature[i] = local.curvature;
            fits[i] = local.fit;
        }
    });
}

}  // namespace

NormalEstimationResult estimate_normals(PointCloud& cloud, const NormalEstimationConfig& config) {
    NormalEstimationResult result;
    if (cloud.size() == 0) {
        result.status = NormalStatus::kEmptyCloud;
        cloud.normals.clear();
        return result;
    }
    CovarianceArrays covariances;
    std::vector<Fit> fits = neighbourhood_covariances(cloud, config, covariances, result);
    solve_normals(covariances, fits, cloud, result);
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
