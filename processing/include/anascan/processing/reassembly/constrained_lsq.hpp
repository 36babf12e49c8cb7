#pragma once
/// \file
/// Linear least squares under linear inequalities: minimise ||A u - b||² subject to
/// C u >= d, the quadratic program of each iteration of the constrained block assembly.
/// Few unknowns (6 per moving block), many constraints (one per contact sample), few of
/// them active: solved in its dual as least distance programming (Lawson & Hanson 1974,
/// "Solving Least Squares Problems", ch. 23): with H = AᵀA = L Lᵀ and z = Lᵀ(u - u0), the
/// problem is min ||z|| subject to G z >= h, whose solution follows from the non-negative
/// least squares problem min ||E λ - f||, λ >= 0, E = [Gᵀ; hᵀ], f = e_{n+1}; NNLS is the
/// Lawson-Hanson active-set method, whose passive set never exceeds n + 1 columns.
/// Every loop is bounded: the inner loop removes one passive column per pass (at most
/// n + 1 passes), the outer loop adds one column per iteration and stops after
/// nnls_iteration_cap() iterations (Lawson & Hanson's 3 × columns, the bound their
/// NNLS and SciPy's use; exact arithmetic ends far sooner, about one iteration per
/// active constraint), reported as kIterationLimit with the last iterate.
/// A zero NNLS residual certifies that the constraints are infeasible; the constraints
/// with λ > 0 are then the contradicting ones.
///
/// Pure computation on Eigen; deterministic.

#include <Eigen/Core>
#include <vector>

namespace anascan::reassembly {

enum class QpStatus { kOptimal, kInfeasible, kIterationLimit };

struct QpResult {
    QpStatus status = QpStatus::kOptimal;
    Eigen::VectorXd u;        ///< The minimiser (the unconstrained one if infeasible).
    std::vector<int> active;  ///< Constraints with λ > 0 (the certificate if infeasible).
    int iterations = 0;       ///< NNLS outer iterations.
};

struct QpConfig {
    double damping = 1e-12;  ///< Added to AᵀA's diagonal, relative to its largest entry.
    int max_iterations = 0;  ///< NNLS outer iterations; 0: nnls_iteration_cap(constraints).
};

/// min ||A u - b||² subject to C u >= d (A: r × n, C: m × n). With m = 0 the least-squares
/// solution. A rank-deficient A is regularised by `damping`.
QpResult solve_constrained_lsq(const Eigen::MatrixXd& A, const Eigen::VectorXd& b,
                               const Eigen::MatrixXd& C, const Eigen::VectorXd& d,
                               const QpConfig& config = {});

/// The same problem given by its normal equations: min ½ uᵀH u - gᵀu subject to C u >= d,
/// H symmetric positive semi-definite.
QpResult solve_constrained_normal(const Eigen::MatrixXd& H, const Eigen::VectorXd& g,
                                  const Eigen::MatrixXd& C, const Eigen::VectorXd& d,
                                  const QpConfig& config = {});

/// The default bound on NNLS outer iterations for `columns` unknowns: 3 × (columns + 1).
int nnls_iteration_cap(int columns);

/// Non-negative least squares min ||E x - f||, x >= 0 (Lawson-Hanson active set).
/// Returns the number of outer iterations; `x` receives the solution.
int nnls(const Eigen::MatrixXd& E, const Eigen::VectorXd& f, Eigen::VectorXd& x,
         int max_iterations = 0);

}  // namespace anascan::reassembly
