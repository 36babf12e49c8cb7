// Least squares under linear inequalities through least distance programming and
// Lawson-Hanson NNLS (see the header).
#include "anascan/processing/reassembly/constrained_lsq.hpp"

#include <Eigen/Cholesky>
#include <Eigen/QR>
#include <algorithm>
#include <cmath>

namespace anascan::reassembly {
namespace {

// Least squares on the passive columns: s_P = argmin ||E_P s - f||, zero elsewhere.
Eigen::VectorXd passive_solution(const Eigen::MatrixXd& E, const Eigen::VectorXd& f,
                                 const std::vector<int>& passive) {
    Eigen::MatrixXd Ep(E.rows(), Eigen::Index(passive.size()));
    for (std::size_t k = 0; k < passive.size(); ++k) Ep.col(Eigen::Index(k)) = E.col(passive[k]);
    const Eigen::VectorXd sp = Ep.colPivHouseholderQr().solve(f);
    Eigen::VectorXd s = Eigen::VectorXd::Zero(E.cols());
    for (std::size_t k = 0; k < passive.size(); ++k) s[passive[k]] = sp[Eigen::Index(k)];
    return s;
}

// The inner loop: step toward the passive solution until it is positive. Every pass that
// does not end the loop takes the blocking index out of the passive set, exactly (the
// degenerate-step guard: a zero step, or rounding that leaves it at 1e-17, still removes
// it), so the loop ends after at most |passive| passes.
void inner_loop(const Eigen::MatrixXd& E, const Eigen::VectorXd& f, std::vector<int>& passive,
                Eigen::VectorXd& x) {
    while (!passive.empty()) {
        const Eigen::VectorXd s = passive_solution(E, f, passive);
        double alpha = 1.0;
        int blocking = -1;
        for (int i : passive) {
            if (s[i] > 0.0) continue;
            const double a = x[i] - s[i] > 0.0 ? x[i] / (x[i] - s[i]) : 0.0;
            if (blocking < 0 || a < alpha) alpha = a, blocking = i;
        }
        if (blocking < 0) {
            x = s;
            return;
        }
        x += std::max(0.0, alpha) * (s - x);
        x[blocking] = 0.0;
        std::erase_if(passive, [&](int i) {
            if (x[i] > 1e-15) return false;
            x[i] = 0.0;
            return true;
        });
    }
}

}  // namespace

int nnls_iteration_cap(int columns) { return 3 * (columns + 1); }

int nnls(const Eigen::MatrixXd& E, const Eigen::VectorXd& f, Eigen::VectorXd& x,
         int max_iterations) {
    const Eigen::Index m = E.cols();
    x = Eigen::VectorXd::Zero(m);
    if (max_iterations <= 0) max_iterations = nnls_iteration_cap(int(m));
    const double tol = 1e-12 * std::max(1.0, E.cwiseAbs().maxCoeff()) * std::max(1.0, f.norm());
    std::vector<int> passive;
    std::vector<char> in_passive(std::size_t(m), 0), refused(std::size_t(m), 0);
    int it = 0;
    for (; it < max_iterations; ++it) {
        const Eigen::VectorXd w = E.transpose() * (f - E * x);
        Eigen::Index best = -1;
        for (Eigen::Index j = 0; j < m; ++j)
            if (!in_passive[j] && !refused[j] && w[j] > tol && (best < 0 || w[j] > w[best]))
                best = j;
        if (best < 0) break;
        passive.push_back(int(best));
        inner_loop(E, f, passive, x);
        if (x[best] <= 0.0) refused[best] = 1;  // Numerically dependent column: not again.
        std::fill(in_passive.begin(), in_passive.end(), 0);
        for (int i : passive) in_passive[i] = 1;
        if (!refused[best]) std::fill(refused.begin(), refused.end(), 0);
    }
    return it;
}

QpResult solve_constrained_normal(const Eigen::MatrixXd& H, const Eigen::VectorXd& g,
                                  const Eigen::MatrixXd& C, const Eigen::VectorXd& d,
                                  const QpConfig& config) {
    const Eigen::Index n = H.rows();
    Eigen::MatrixXd Hd = H;
    const double scale = std::max(1e-300, H.diagonal().cwiseAbs().maxCoeff());
    Hd.diagonal().array() += config.damping * scale;
    const Eigen::LLT<Eigen::MatrixXd> llt(Hd);
    QpResult out;
    out.u = llt.solve(g);
    if (C.rows() == 0) return out;
    // G = C L^-T and h = d - C u0, each row normalised.
    const Eigen::MatrixXd Lt = llt.matrixU();
    Eigen::MatrixXd G = Lt.transpose().triangularView<Eigen::Lower>().solve(C.transpose());
    Eigen::VectorXd h = d - C * out.u;
    Eigen::MatrixXd E(n + 1, C.rows());
    for (Eigen::Index i = 0; i < C.rows(); ++i) {
        const double norm = std::max(1e-300, G.col(i).norm());
        E.col(i).head(n) = G.col(i) / norm;
        E(n, i) = h[i] / norm;
    }
    Eigen::VectorXd f = Eigen::VectorXd::Zero(n + 1);
    f[n] = 1.0;
    Eigen::VectorXd lambda;
    const int cap =
        config.max_iterations > 0 ? config.max_iterations : nnls_iteration_cap(int(C.rows()));
    out.iterations = nnls(E, f, lambda, cap);
    for (Eigen::Index i = 0; i < lambda.size(); ++i)
        if (lambda[i] > 0.0) out.active.push_back(int(i));
    const Eigen::VectorXd r = E * lambda - f;
    // Infeasible: the residual vanishes. Its last entry is what divides the solution below;
    // exactly opposed constraints (a block too wide for its gap, along one face plane each
    // side) leave the head at rounding level and the last entry near zero, which would
    // read as a step of norm 1e7 (-r[n] is 1 - h·λ, between 0 and 1).
    if (r.norm() < 1e-9 || -r[n] < 1e-9) {
        out.status = QpStatus::kInfeasible;
        return out;
    }
    if (out.iterations >= cap) out.status = QpStatus::kIterationLimit;
    const Eigen::VectorXd z = -r.head(n) / r[n];
    out.u += Lt.triangularView<Eigen::Upper>().solve(z);
    return out;
}

QpResult solve_constrained_lsq(const Eigen::MatrixXd& A, const Eigen::VectorXd& b,
                               const Eigen::MatrixXd& C, const Eigen::VectorXd& d,
                               const QpConfig& config) {
    return solve_constrained_normal(A.transpose() * A, A.transpose() * b, C, d, config);
}

}  // namespace anascan::reassembly
