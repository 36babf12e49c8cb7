#pragma once
// Random constrained least-squares problems for the QP tests.
#include <Eigen/Core>
#include <cmath>
#include <random>

namespace anascan::reassembly::testing {

struct Problem {
    Eigen::MatrixXd A, C;
    Eigen::VectorXd b, d;
};

// Random least squares with constraints that cut off its unconstrained minimiser.
inline Problem random_problem(int n, int r, int m, unsigned seed) {
    std::mt19937 rng(seed);
    std::normal_distribution<double> N(0.0, 1.0);
    Problem p{Eigen::MatrixXd(r, n), Eigen::MatrixXd(m, n), Eigen::VectorXd(r), Eigen::VectorXd(m)};
    for (int i = 0; i < r * n; ++i) p.A.data()[i] = N(rng);
    for (int i = 0; i < r; ++i) p.b[i] = N(rng);
    for (int i = 0; i < m * n; ++i) p.C.data()[i] = N(rng);
    for (int i = 0; i < m; ++i) p.d[i] = -std::abs(N(rng)) - 0.1;  // The origin is feasible.
    return p;
}

inline double objective(const Problem& p, const Eigen::VectorXd& u) {
    return (p.A * u - p.b).squaredNorm();
}

}  // namespace anascan::reassembly::testing
