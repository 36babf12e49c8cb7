#pragma once
/// \file
/// Private to normals.cpp: the smallest eigenpair of many local covariances at once. The
/// covariances are stored as arrays, one entry per point, so that the solve runs over
/// points in SIMD lanes (AVX2 where the CPU has it: four points per instruction, same
/// results as the plain loop); the few points it cannot settle are solved one at a time.

#include <Eigen/Core>
#include <array>
#include <cstddef>
#include <cstdint>
#include <memory>
#include <vector>

namespace anascan::normals_detail {

/// Covariances scaled to unit trace, one record per point of the six distinct entries
/// (xx, yy, zz, xy, xz, yz): points are filled in neighbour-search order, so one record
/// is one cache line touched, not six.
struct CovarianceArrays {
    std::unique_ptr<std::array<float, 6>[]> entries;

    void resize(std::size_t n);
    void set(std::size_t i, const Eigen::Matrix3d& unit);
    Eigen::Matrix3d get(std::size_t i) const;
};

/// Where solve_smallest writes: the eigenvector (not normalised), the eigenvalue, and
/// whether it settled, each an array of the batch's size.
struct EigenpairArrays {
    float* __restrict x;
    float* __restrict y;
    float* __restrict z;
    float* __restrict lambda;
    std::uint8_t* __restrict settled;
};

/// The eigenpair of the smallest eigenvalue of points [begin, end), by a fixed number of
/// Newton steps on the characteristic cubic (see smallest_eigenpair), written for point i
/// at i - begin. `settled` is 1 where the last step was negligible and the eigenvector is
/// well conditioned, else 0 (then the other outputs are meaningless: use
/// smallest_eigenpair).
void solve_smallest(const CovarianceArrays& a, std::size_t begin, std::size_t end,
                    const EigenpairArrays& out);

/// The same for one matrix, iterating to convergence: false where the eigenvector is
/// ill-conditioned (the two smallest eigenvalues nearly equal), for the general solver.
bool smallest_eigenpair(const Eigen::Matrix3d& a, double& lambda, Eigen::Vector3d& vector);

}  // namespace anascan::normals_detail
