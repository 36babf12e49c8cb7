#include "anascan/processing/registration/multiview/link_compression.hpp"

#include <Eigen/Cholesky>
#include <cmath>

#include "registration/multiview/steps.hpp"

namespace anascan {
namespace {

using Vector6d = Eigen::Matrix<double, 6, 1>;
using Matrix6d = Eigen::Matrix<double, 6, 6>;

// The multi-view solve's own rule: a correspondence it would ignore is not kept either.
using multiview_detail::usable;

/// Every k-th usable correspondence, k chosen so that at most `max_count` remain.
std::vector<FineCorrespondence> evenly_spread(const std::vector<FineCorrespondence>& all,
                                              std::size_t max_count, double& weight_all,
                                              double& weight_kept) {
    std::size_t count = 0;
    weight_all = 0.0;
    for (const FineCorrespondence& c : all) {
        if (!usable(c)) continue;
        ++count;
        weight_all += c.weight;
    }
    const std::size_t step = (count + max_count - 1) / max_count;
    std::vector<FineCorrespondence> kept;
    kept.reserve(max_count);
    weight_kept = 0.0;
    std::size_t k = 0;
    for (const FineCorrespondence& c : all) {
        if (!usable(c) || k++ % step != 0) continue;
        kept.push_back(c);
        weight_kept += c.weight;
    }
    return kept;
}

/// Derivative of a residual with respect to a small motion of the source (rotation about
/// `centre_m` scaled by `length_m`, then translation); only its column space matters.
Vector6d jacobian(const Eigen::Vector3d& X, const Eigen::Vector3d& n,
                  const Eigen::Vector3d& centre_m, double length_m) {
    Vector6d J;
    J.head<3>() = (X - centre_m).cross(n) / length_m;
    J.tail<3>() = n;
    return J;
}

/// Moves the target points along their normals by δ = J (JᵀWJ)⁻¹ JᵀW r, the smallest
/// change of the residuals r that leaves no gradient (JᵀW(r - δ) = 0).
void remove_gradient(std::vector<FineCorrespondence>& kept, const Pose& T_target_source) {
    Eigen::Vector3d centre = Eigen::Vector3d::Zero();
    for (const FineCorrespondence& c : kept) centre += T_target_source * c.source_point_m;
    centre /= static_cast<double>(kept.size());
    double spread_sq = 0.0;
    for (const FineCorrespondence& c : kept)
        spread_sq += (T_target_source * c.source_point_m - centre).squaredNorm();
    const double length_m = std::max(1e-6, std::sqrt(spread_sq / double(kept.size())));
    Matrix6d H = Matrix6d::Zero();
    Vector6d g = Vector6d::Zero();
    std::vector<Vector6d> J(kept.size());
    std::vector<double> r(kept.size());
    for (std::size_t i = 0; i < kept.size(); ++i) {
        const FineCorrespondence& c = kept[i];
        const Eigen::Vector3d X = T_target_source * c.source_point_m;
        const Eigen::Vector3d n = c.target_normal.cast<double>().normalized();
        J[i] = jacobian(X, n, centre, length_m);
        r[i] = (X - c.target_point_m).dot(n);
        H.noalias() += c.weight * J[i] * J[i].transpose();
        g.noalias() += c.weight * r[i] * J[i];
    }
    // A flat overlap leaves H singular: a small ridge keeps the solve finite, and δ has no
    // component along the free directions anyway (their J is zero for every point).
    H.diagonal().array() += 1e-12 * std::max(H.trace(), 1e-30);
    const Vector6d a = H.ldlt().solve(g);
    for (std::size_t i = 0; i < kept.size(); ++i) {
        const double delta = J[i].dot(a);
        FineCorrespondence& c = kept[i];
        c.target_point_m += delta * c.target_normal.cast<double>().normalized();
        c.residual_m = r[i] - delta;
    }
}

}  // namespace

std::vector<FineCorrespondence> compress_link(std::vector<FineCorrespondence> all,
                                              const Pose& T_target_source, std::size_t max_count) {
    if (max_count == 0 || all.size() <= max_count) return all;
    double weight_all = 0.0, weight_kept = 0.0;
    std::vector<FineCorrespondence> kept = evenly_spread(all, max_count, weight_all, weight_kept);
    if (kept.size() < 6 || weight_kept <= 0.0) return all;
    const double scale = weight_all / weight_kept;
    for (FineCorrespondence& c : kept) c.weight *= scale;
    remove_gradient(kept, T_target_source);
    return kept;
}

}  // namespace anascan
