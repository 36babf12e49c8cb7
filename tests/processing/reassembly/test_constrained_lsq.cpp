// The assembly's QP solver (least distance programming through Lawson-Hanson NNLS) on
// problems with known solutions, random problems checked for optimality, infeasible
// constraints, and agreement with Debian's Clp on the same problems when Clp is present.
#include <gtest/gtest.h>

#include <Eigen/QR>
#include <random>

#include "anascan/processing/reassembly/constrained_lsq.hpp"
#include "random_qp.hpp"

namespace anascan::reassembly {
namespace {

using testing::objective;
using testing::Problem;
using testing::random_problem;

TEST(ConstrainedLsq, KnownTwoDimensionalSolution) {
    // min (x-2)² + (y-2)² subject to -x - y >= -2: the point (1, 1).
    const Eigen::MatrixXd A = Eigen::MatrixXd::Identity(2, 2);
    const Eigen::MatrixXd C = Eigen::RowVector2d(-1.0, -1.0);
    const QpResult r =
        solve_constrained_lsq(A, Eigen::Vector2d(2, 2), C, Eigen::VectorXd::Constant(1, -2.0));
    ASSERT_EQ(r.status, QpStatus::kOptimal);
    EXPECT_NEAR(r.u[0], 1.0, 1e-9);
    EXPECT_NEAR(r.u[1], 1.0, 1e-9);
    EXPECT_EQ(r.active, std::vector<int>{0});
}

TEST(ConstrainedLsq, InactiveConstraintsLeaveTheLeastSquaresSolution) {
    Problem p = random_problem(6, 30, 40, 3);
    const Eigen::VectorXd ls = p.A.colPivHouseholderQr().solve(p.b);
    p.d = p.C * ls - Eigen::VectorXd::Constant(p.d.size(), 0.1);
    const QpResult r = solve_constrained_lsq(p.A, p.b, p.C, p.d);
    ASSERT_EQ(r.status, QpStatus::kOptimal);
    EXPECT_LT((r.u - ls).norm(), 1e-8);
    EXPECT_TRUE(r.active.empty());
}

TEST(ConstrainedLsq, RandomProblemsAreFeasibleAndOptimal) {
    for (unsigned seed = 1; seed <= 10; ++seed) {
        const Problem p = random_problem(12, 60, 300, seed);
        const QpResult r = solve_constrained_lsq(p.A, p.b, p.C, p.d);
        ASSERT_EQ(r.status, QpStatus::kOptimal) << seed;
        EXPECT_GT((p.C * r.u - p.d).minCoeff(), -1e-8) << seed;
        // No feasible point nearby is better (convex: a local check is a global one).
        std::mt19937 rng(seed);
        std::normal_distribution<double> N(0.0, 1.0);
        for (int k = 0; k < 200; ++k) {
            Eigen::VectorXd v(12);
            for (double& x : v) x = N(rng);
            const Eigen::VectorXd u = r.u + 1e-3 * v;
            if ((p.C * u - p.d).minCoeff() >= 0.0) {
                EXPECT_GE(objective(p, u), objective(p, r.u) - 1e-10);
            }
        }
    }
}

TEST(ConstrainedLsq, ContradictingConstraintsAreInfeasible) {
    // x >= 1 and -x >= 1 (x <= -1), plus harmless ones on y.
    const Eigen::MatrixXd A = Eigen::MatrixXd::Identity(2, 2);
    Eigen::MatrixXd C(4, 2);
    C << 0, 1, 1, 0, 0, -1, -1, 0;
    const QpResult r =
        solve_constrained_lsq(A, Eigen::Vector2d(0, 0), C, Eigen::Vector4d(-5, 1, -5, 1));
    EXPECT_EQ(r.status, QpStatus::kInfeasible);
    EXPECT_EQ(r.active, (std::vector<int>{1, 3}));
}

TEST(ConstrainedLsq, RankDeficientObjectiveIsRegularised) {
    // Only x is observed; y is free but pushed by y >= 0.5.
    Eigen::MatrixXd A(1, 2);
    A << 1, 0;
    const Eigen::MatrixXd C = Eigen::RowVector2d(0, 1);
    const QpResult r = solve_constrained_lsq(A, Eigen::VectorXd::Constant(1, 3.0), C,
                                             Eigen::VectorXd::Constant(1, 0.5));
    ASSERT_EQ(r.status, QpStatus::kOptimal);
    EXPECT_NEAR(r.u[0], 3.0, 1e-6);
    EXPECT_NEAR(r.u[1], 0.5, 1e-6);
}

// A degenerate vertex: the same constraint many times over and near copies of it (ties in
// the step length, zero steps). The solver ends, feasible and optimal, well within its cap.
TEST(ConstrainedLsq, DegenerateRepeatedConstraintsEnd) {
    const Eigen::MatrixXd A = Eigen::MatrixXd::Identity(3, 3);
    const Eigen::Vector3d b(2, 2, 2);
    Eigen::MatrixXd C(300, 3);
    Eigen::VectorXd d(300);
    std::mt19937 rng(3);
    std::normal_distribution<double> N(0.0, 1e-13);
    for (int i = 0; i < 300; ++i) {
        C.row(i) = Eigen::RowVector3d(-1.0 + N(rng), -1.0, i % 3 == 0 ? 0.0 : -1.0);
        d[i] = -1.0 + (i % 2 == 0 ? 0.0 : N(rng));
    }
    const QpResult r = solve_constrained_lsq(A, b, C, d);
    ASSERT_EQ(r.status, QpStatus::kOptimal);
    EXPECT_LT(r.iterations, nnls_iteration_cap(300));
    EXPECT_GT((C * r.u - d).minCoeff(), -1e-8);
    // The projection of (2, 2, 2) onto x + y <= 1, x + y + z <= 1: onto the second plane,
    // (1/3, 1/3, 1/3), where the first holds (x + y = 2/3).
    for (int k = 0; k < 3; ++k) EXPECT_NEAR(r.u[k], 1.0 / 3.0, 1e-6) << k;
}

// At its cap the solver says so (and the assembly turns that into "not converged").
TEST(ConstrainedLsq, TheIterationCapIsReported) {
    const Problem p = random_problem(12, 60, 300, 5);
    const QpResult full = solve_constrained_lsq(p.A, p.b, p.C, p.d);
    ASSERT_EQ(full.status, QpStatus::kOptimal);
    ASSERT_GT(full.iterations, 1);
    const QpResult capped = solve_constrained_lsq(p.A, p.b, p.C, p.d, {.max_iterations = 1});
    EXPECT_EQ(capped.status, QpStatus::kIterationLimit);
    EXPECT_EQ(capped.iterations, 1);
}

}  // namespace
}  // namespace anascan::reassembly
