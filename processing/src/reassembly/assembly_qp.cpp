// The quadratic program of one assembly iteration: the motion frames, the weighted normal
// equations of the three terms and the non-penetration constraints (assembly_steps.hpp).
#include <algorithm>
#include <cmath>

#include "assembly_steps.hpp"

namespace anascan::reassembly::assembly_detail {

Frames frames_of(const AssemblyProblem& p, const std::vector<Pose>& T) {
    Frames f;
    for (std::size_t b = 0; b < p.blocks.size(); ++b) {
        Eigen::Vector3d c = Eigen::Vector3d::Zero();
        const auto& pts = p.blocks[b].points.positions;
        for (const auto& x : pts) c += x.cast<double>();
        c /= std::max<double>(1.0, double(pts.size()));
        double r2 = 0.0;
        for (const auto& x : pts) r2 += (x.cast<double>() - c).squaredNorm();
        f.reference_m.push_back(T[b] * c);
        f.length_m.push_back(
            std::max(1e-3, std::sqrt(r2 / std::max<double>(1.0, double(pts.size())))));
    }
    return f;
}

Eigen::VectorXd rhs_of(const std::vector<Row>& rows, double weight) {
    Eigen::VectorXd b(Eigen::Index(rows.size()));
    for (std::size_t i = 0; i < rows.size(); ++i) b[Eigen::Index(i)] = weight * rows[i].rhs;
    return b;
}

Eigen::MatrixXd IterationQp::H() const { return H_reg + H_cp + H_cl; }
Eigen::VectorXd IterationQp::g() const { return g_reg + g_cp + g_cl; }

IterationQp iteration_qp(const Rows& rows, const Prepared& prep, const Frames& frames,
                         bool constrained) {
    auto weight = [](const std::vector<Row>& r) {  // Each term a mean: they enter equally.
        return 1.0 / std::sqrt(std::max<double>(1.0, double(r.size())));
    };
    IterationQp q;
    auto term = [&](const std::vector<Row>& r, Eigen::MatrixXd& H, Eigen::VectorXd& g) {
        const double w = weight(r);
        const Eigen::MatrixXd A = row_matrix(r, prep, frames, w);
        H = A.transpose() * A;
        g = A.transpose() * rhs_of(r, w);
    };
    term(rows.contact, q.H_reg, q.g_reg);
    term(rows.coplanar, q.H_cp, q.g_cp);
    term(rows.colinear, q.H_cl, q.g_cl);
    q.C = Eigen::MatrixXd(0, q.H_reg.cols());
    if (constrained)
        q.C = row_matrix(rows.contact, prep, frames, 1.0), q.d = rhs_of(rows.contact, 1.0);
    return q;
}

}  // namespace anascan::reassembly::assembly_detail
