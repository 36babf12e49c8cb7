// The assembly's QP solver against Debian's Clp (quadratic primal simplex) on the same
// random problems: the solutions agree.
#include <gtest/gtest.h>

#include "anascan/processing/reassembly/constrained_lsq.hpp"
#include "clp_qp.hpp"
#include "random_qp.hpp"

namespace anascan::reassembly {
namespace {

using testing::Problem;
using testing::random_problem;

TEST(ConstrainedLsq, AgreesWithClp) {
    for (unsigned seed = 1; seed <= 5; ++seed) {
        const Problem p = random_problem(18, 80, 500, seed);
        const QpResult r = solve_constrained_lsq(p.A, p.b, p.C, p.d);
        const testing::ClpSolution clp =
            testing::solve_qp_with_clp(p.A.transpose() * p.A, p.A.transpose() * p.b, p.C, p.d);
        ASSERT_EQ(clp.status, 0) << seed;
        ASSERT_EQ(r.status, QpStatus::kOptimal) << seed;
        EXPECT_LT((r.u - clp.u).norm(), 1e-6 * (1.0 + clp.u.norm())) << seed;
    }
}

}  // namespace
}  // namespace anascan::reassembly
