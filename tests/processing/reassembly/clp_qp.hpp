#pragma once
// Debian's Clp (COIN-OR) as the peer of the assembly's QP solver: min ½uᵀHu - gᵀu subject
// to C u >= d by Clp's quadratic primal simplex (the Hessian's upper triangle, column-wise).
// Only for tests and benchmarks (ANASCAN_HAVE_CLP).
#include <ClpSimplex.hpp>
#include <CoinPackedMatrix.hpp>
#include <Eigen/Core>
#include <vector>

namespace anascan::reassembly::testing {

struct ClpSolution {
    Eigen::VectorXd u;
    int status = 0;  ///< Clp's: 0 optimal, 1 primal infeasible, ...
};

inline ClpSolution solve_qp_with_clp(const Eigen::MatrixXd& H, const Eigen::VectorXd& g,
                                     const Eigen::MatrixXd& C, const Eigen::VectorXd& d) {
    const int n = int(H.cols()), m = int(C.rows());
    std::vector<int> rows, cols;
    std::vector<double> values;
    for (int c = 0; c < n; ++c)
        for (int r = 0; r < m; ++r)
            if (C(r, c) != 0.0) rows.push_back(r), cols.push_back(c), values.push_back(C(r, c));
    CoinPackedMatrix A(true, rows.data(), cols.data(), values.data(), CoinBigIndex(values.size()));
    A.setDimensions(m, n);
    const std::vector<double> col_lo(std::size_t(n), -COIN_DBL_MAX),
        col_hi(std::size_t(n), COIN_DBL_MAX);
    const std::vector<double> row_hi(std::size_t(m), COIN_DBL_MAX);
    const Eigen::VectorXd objective = -g;
    ClpSimplex model;
    model.setLogLevel(0);
    model.loadProblem(A, col_lo.data(), col_hi.data(), objective.data(), d.data(), row_hi.data());
    std::vector<CoinBigIndex> start;
    std::vector<int> index;
    std::vector<double> element;
    for (int c = 0; c < n; ++c) {
        start.push_back(CoinBigIndex(index.size()));
        for (int r = c; r < n; ++r) index.push_back(r), element.push_back(H(r, c));
    }
    start.push_back(CoinBigIndex(index.size()));
    model.loadQuadraticObjective(n, start.data(), index.data(), element.data());
    model.primal();
    ClpSolution out;
    out.status = model.status();
    out.u = Eigen::Map<const Eigen::VectorXd>(model.primalColumnSolution(), n);
    return out;
}

}  // namespace anascan::reassembly::testing
