#include "normals_solve.hpp"

#include <Eigen/Geometry>
#include <Eigen/LU>
#include <array>
#include <cmath>

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

CovarianceView view(const CovarianceArrays& a) {
    return {a.xx.data(), a.yy.data(), a.zz.data(), a.xy.data(), a.xz.data(), a.yz.data()};
}

// One point of the batch, its outputs at o: plain arithmetic and selects only, so that the
// loop over points vectorises (no branch, no call; sqrt is left to the caller).
inline void solve_one(const CovarianceView& a, std::size_t i, std::size_t o,
                      const EigenpairArrays& out) {
    const double xx = a.xx[i], yy = a.yy[i], zz = a.zz[i], xy = a.xy[i], xz = a.xz[i], yz = a.yz[i];
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

void solve_plain(const CovarianceView a, std::size_t begin, std::size_t end,
                 const EigenpairArrays out) {
    for (std::size_t i = begin; i < end; ++i) solve_one(a, i, i - begin, out);
}

#if defined(__x86_64__) && defined(__GNUC__)
__attribute__((target("avx2"))) void solve_avx2(const CovarianceView a, std::size_t begin,
                                                std::size_t end, const EigenpairArrays out) {
    for (std::size_t i = begin; i < end; ++i) solve_one(a, i, i - begin, out);
}

bool have_avx2() {
    static const bool avx2 = __builtin_cpu_supports("avx2");
    return avx2;
}
#endif

}  // namespace

void CovarianceArrays::resize(std::size_t n) {
    for (std::vector<float>* v : {&xx, &yy, &zz, &xy, &xz, &yz}) v->assign(n, 0.0f);
}

void CovarianceArrays::set(std::size_t i, const Eigen::Matrix3d& unit) {
    xx[i] = float(unit(0, 0));
    yy[i] = float(unit(1, 1));
    zz[i] = float(unit(2, 2));
    xy[i] = float(unit(0, 1));
    xz[i] = float(unit(0, 2));
    yz[i] = float(unit(1, 2));
}

Eigen::Matrix3d CovarianceArrays::get(std::size_t i) const {
    Eigen::Matrix3d m;
    m << xx[i], xy[i], xz[i], xy[i], yy[i], yz[i], xz[i], yz[i], zz[i];
    return m;
}

void solve_smallest(const CovarianceArrays& a, std::size_t begin, std::size_t end,
                    const EigenpairArrays& out) {
#if defined(__x86_64__) && defined(__GNUC__)
    if (have_avx2()) return solve_avx2(view(a), begin, end, out);
#endif
    solve_plain(view(a), begin, end, out);
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
