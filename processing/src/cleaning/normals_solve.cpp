#include "cleaning/normals_solve.hpp"

#include <Eigen/Geometry>
#include <Eigen/LU>
#include <array>
#include <cmath>

#include "core/cpu_features.hpp"

namespace anascan::normals_detail {
namespace {

constexpr double kMinGapProduct = 1e-8;  // (λ1 - λ0)(λ2 - λ0) at unit trace.
constexpr double kSettledStep = 1e-12;   // Last Newton step, at unit trace.
// Newton steps after the first (c0 / c1) in the batch solve: a surface's neighbourhood
// (λ0 well below λ1) settles in two or three; the rest go to the scalar solve.
constexpr int kBatchSteps = 4;

struct CovarianceView {  // The arrays' data, read only (the loop then keeps them in registers).
    const float* __restrict xx;
    const float* __restrict yy;
    const float* __restrict zz;
    const float* __restrict xy;
    const float* __restrict xz;
    const float* __restrict yz;
};

// Points [begin, end) as arrays, so that the batch loop loads whole vectors.
struct CovarianceBatch {
    std::vector<float> xx, yy, zz, xy, xz, yz;

    CovarianceBatch(const CovarianceArrays& a, std::size_t begin, std::size_t end) {
        const std::size_t m = end - begin;
        for (std::vector<float>* v : {&xx, &yy, &zz, &xy, &xz, &yz}) v->resize(m);
        for (std::size_t o = 0; o < m; ++o) {
            const std::array<float, 6>& e = a.entries[begin + o];
            xx[o] = e[0];
            yy[o] = e[1];
            zz[o] = e[2];
            xy[o] = e[3];
            xz[o] = e[4];
            yz[o] = e[5];
        }
    }
    CovarianceView view() const {
        return {xx.data(), yy.data(), zz.data(), xy.data(), xz.data(), yz.data()};
    }
};

// Point o of the batch: plain arithmetic and selects only, so that the loop over points
// vectorises (no branch, no call; sqrt is left to the caller).
inline void solve_one(const CovarianceView& a, std::size_t o, const EigenpairArrays& out) {
    const double xx = a.xx[o], yy = a.yy[o], zz = a.zz[o], xy = a.xy[o], xz = a.xz[o], yz = a.yz[o];
    const double c2 = xx + yy + zz;
    const double c1 = xx * yy - xy * xy + xx * zz - xz * xz + yy * zz - yz * yz;
    const double c0 =
        xx * (yy * zz - yz * yz) - xy * (xy * zz - yz * xz) + xz * (xy * yz - yy * xz);
    double x = c0 / c1, step = 1.0, slope = 0.0;
    for (int s = 0; s < kBatchSteps; ++s) {
        slope = (3.0 * x - 2.0 * c2) * x + c1;
        step = (((x - c2) * x + c1) * x - c0) / slope;
        x -= step;
    }
    const double m00 = xx - x, m11 = yy - x, m22 = zz - x;
    // Cross products of the rows of a - x I: each is the eigenvector, scaled.
    const double ax = xy * yz - xz * m11, ay = xz * xy - m00 * yz, az = m00 * m11 - xy * xy;
    const double bx = xy * m22 - xz * yz, by = xz * xz - m00 * m22, bz = m00 * yz - xy * xz;
    const double cx = m11 * m22 - yz * yz, cy = yz * xz - xy * m22, cz = xy * yz - m11 * xz;
    const double na = ax * ax + ay * ay + az * az, nb = bx * bx + by * by + bz * bz,
                 nc = cx * cx + cy * cy + cz * cz;
    // The longest, by selects (no branch): ties keep the earlier, as the scalar solve.
    const bool b_longer = nb > na;
    double vx = b_longer ? bx : ax, vy = b_longer ? by : ay, vz = b_longer ? bz : az;
    double best = b_longer ? nb : na;
    const bool c_longer = nc > best;
    vx = c_longer ? cx : vx;
    vy = c_longer ? cy : vy;
    vz = c_longer ? cz : vz;
    best = c_longer ? nc : best;
    out.x[o] = float(vx);
    out.y[o] = float(vy);
    out.z[o] = float(vz);
    out.lambda[o] = float(x);
    out.settled[o] =
        std::uint8_t((slope > 0.0) & (std::abs(step) <= kSettledStep * c2) &
                     (best > kMinGapProduct * kMinGapProduct) & (x >= -1.0) & (x <= 1.0));
}

void solve_plain(const CovarianceView a, std::size_t m, const EigenpairArrays out) {
    for (std::size_t o = 0; o < m; ++o) solve_one(a, o, out);
}

#if defined(__x86_64__) && defined(__GNUC__)
__attribute__((target("avx2"))) void solve_avx2(const CovarianceView a, std::size_t m,
                                                const EigenpairArrays out) {
    for (std::size_t o = 0; o < m; ++o) solve_one(a, o, out);
}

#endif

}  // namespace

void CovarianceArrays::resize(std::size_t n) {
    entries.reset(new std::array<float, 6>[n]);  // Not zeroed: set() writes before get().
}

void CovarianceArrays::set(std::size_t i, const Eigen::Matrix3d& unit) {
    entries[i] = {float(unit(0, 0)), float(unit(1, 1)), float(unit(2, 2)),
                  float(unit(0, 1)), float(unit(0, 2)), float(unit(1, 2))};
}

Eigen::Matrix3d CovarianceArrays::get(std::size_t i) const {
    const std::array<float, 6>& e = entries[i];
    Eigen::Matrix3d m;
    m << e[0], e[3], e[4], e[3], e[1], e[5], e[4], e[5], e[2];
    return m;
}

void solve_smallest(const CovarianceArrays& a, std::size_t begin, std::size_t end,
                    const EigenpairArrays& out) {
    const CovarianceBatch batch(a, begin, end);
#if defined(__x86_64__) && defined(__GNUC__)
    if (detail::cpu_has_avx2()) return solve_avx2(batch.view(), end - begin, out);
#endif
    solve_plain(batch.view(), end - begin, out);
}

// Newton's method on the characteristic cubic from c0 / c1, its first step from 0 (left
// of the smallest root the cubic rises and is concave, so the iterates climb to it without
// overshooting); the unit eigenvector is the longest cross product of two rows of
// a - lambda I.
bool smallest_eigenpair(const Eigen::Matrix3d& a, double& lambda, Eigen::Vector3d& vector) {
    constexpr int kMaxIterations = 16;
    const double c2 = a.trace();
    const double c1 = a(0, 0) * a(1, 1) - a(0, 1) * a(0, 1) + a(0, 0) * a(2, 2) -
                      a(0, 2) * a(0, 2) + a(1, 1) * a(2, 2) - a(1, 2) * a(1, 2);
    const double c0 = a.determinant();
    if (!(c1 > 0.0)) return false;
    double x = c0 / c1;
    for (int iteration = 0; iteration < kMaxIterations; ++iteration) {
        const double slope = (3.0 * x - 2.0 * c2) * x + c1;
        if (!(slope > 0.0)) return false;
        const double step = (((x - c2) * x + c1) * x - c0) / slope;
        x -= step;
        if (std::abs(step) <= 0.1 * kSettledStep * c2) break;
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

}  // namespace anascan::normals_detail
