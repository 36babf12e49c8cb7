#include "registration/multiview/steps.hpp"

#include <Eigen/Cholesky>
#include <Eigen/Geometry>
#include <Eigen/OrderingMethods>
#include <Eigen/SparseCholesky>
#include <algorithm>
#include <cmath>
#include <deque>

#include "anascan/processing/registration/fine/helical_motion.hpp"

namespace anascan::multiview_detail {
namespace {

// One correspondence mapped into the world frame at the current poses.
struct WorldCorrespondence {
    Eigen::Vector3d X;  // T_world_k x_i.
    Eigen::Vector3d N;  // R_world_j n_i.
    double d = 0.0;     // (X - Y)·N, metres.
};

WorldCorrespondence to_world(const FineCorrespondence& c, const Pose& T_world_j,
                             const Pose& T_world_k) {
    WorldCorrespondence w;
    w.X = T_world_k * c.source_point_m;
    w.N = T_world_j.linear() * c.target_normal.cast<double>();
    w.d = (w.X - T_world_j * c.target_point_m).dot(w.N);
    return w;
}

// Derivative of the residual with respect to u_s = (c_s L, c̄'_s) of the scan that carries
// the source point: the velocity v_s(X)·N (negated for the target scan, see the docs).
Vector6d jacobian(const WorldCorrespondence& w, const Eigen::Vector3d& reference_m,
                  double length_m) {
    Vector6d J;
    J.head<3>() = (w.X - reference_m).cross(w.N) / length_m;
    J.tail<3>() = w.N;
    return J;
}

// Accumulates one link's 12×12 normal equations (source block first, then target).
void accumulate_link(const MultiviewLink& link, std::span<const Pose> T_world_scan,
                     const Parametrisation& param, Eigen::Matrix<double, 12, 12>& H,
                     Eigen::Matrix<double, 12, 1>& g) {
    const std::size_t j = link.target_index;
    const std::size_t k = link.source_index;
    for (const FineCorrespondence& c : link.correspondences) {
        if (!usable(c)) continue;
        const WorldCorrespondence w = to_world(c, T_world_scan[j], T_world_scan[k]);
        Eigen::Matrix<double, 12, 1> J;
        J.head<6>() = jacobian(w, param.reference_m[k], param.length_m);
        J.tail<6>() = -jacobian(w, param.reference_m[j], param.length_m);
        H.noalias() += c.weight * J * J.transpose();
        g.noalias() += c.weight * w.d * J;
    }
}

// Adds H_ab (block rows a, columns b) to the system, keeping only a <= b.
void add_block(BlockSystem& system, int a, int b, const Matrix6d& H_ab) {
    if (a < 0 || b < 0) return;
    if (a == b) {
        system.diagonal[a] += H_ab;
    } else if (a < b) {
        auto [it, inserted] = system.off_diagonal.try_emplace({a, b}, Matrix6d::Zero());
        it->second += H_ab;
    } else {
        add_block(system, b, a, H_ab.transpose());
    }
}

double tikhonov(const BlockSystem& system, double relative) {
    double trace = 0.0;
    for (const Matrix6d& D : system.diagonal) trace += D.trace();
    const double mean = trace / (6.0 * static_cast<double>(system.diagonal.size()));
    return relative * (mean > 0.0 ? mean : 1.0);
}

double pivot_ratio(const Eigen::VectorXd& pivots) {
    const double largest = pivots.cwiseAbs().maxCoeff();
    return largest > 0.0 ? pivots.cwiseAbs().minCoeff() / largest : 0.0;
}

Eigen::VectorXd stacked_rhs(const BlockSystem& system) {
    Eigen::VectorXd rhs(6 * system.gradient.size());
    for (std::size_t s = 0; s < system.gradient.size(); ++s) {
        rhs.segment<6>(6 * s) = -system.gradient[s];
    }
    return rhs;
}

Eigen::VectorXd solve_dense(const BlockSystem& system, double lambda, double& ratio) {
    const Eigen::Index n = 6 * static_cast<Eigen::Index>(system.diagonal.size());
    Eigen::MatrixXd H = Eigen::MatrixXd::Zero(n, n);
    for (std::size_t s = 0; s < system.diagonal.size(); ++s) {
        H.block<6, 6>(6 * s, 6 * s) = system.diagonal[s];
    }
    for (const auto& [ab, block] : system.off_diagonal) {
        H.block<6, 6>(6 * ab.first, 6 * ab.second) = block;
        H.block<6, 6>(6 * ab.second, 6 * ab.first) = block.transpose();
    }
    H.diagonal().array() += lambda;
    const Eigen::LDLT<Eigen::MatrixXd> ldlt(H);
    ratio = pivot_ratio(ldlt.vectorD());
    return ldlt.solve(stacked_rhs(system));
}

// The sparse path keeps its memory small at thousands of scans (docs/scan-registration.md,
// "Scale"): no triplet list and no full symmetric copy of H. The blocks are
// ordered by approximate minimum degree on the block graph (one node per scan: 36 times
// fewer entries than the 6N scalar pattern), and only the upper triangle of the permuted
// H + λI is built, directly in compressed columns; the factorisation then uses it as it is
// (64-bit indices and the natural ordering, so Eigen neither copies nor reorders it).
using UpperMatrix = Eigen::SparseMatrix<double, Eigen::ColMajor, Eigen::Index>;

// Elimination order: the old block at each new position.
std::vector<int> block_order(const BlockSystem& system) {
    const int blocks = static_cast<int>(system.diagonal.size());
    std::vector<Eigen::Triplet<double>> entries;
    entries.reserve(system.diagonal.size() + system.off_diagonal.size());
    for (int b = 0; b < blocks; ++b) entries.emplace_back(b, b, 1.0);
    for (const auto& entry : system.off_diagonal) {
        entries.emplace_back(entry.first.first, entry.first.second, 1.0);
    }
    Eigen::SparseMatrix<double> pattern(blocks, blocks);
    pattern.setFromTriplets(entries.begin(), entries.end());
    Eigen::PermutationMatrix<Eigen::Dynamic, Eigen::Dynamic, int> order;
    Eigen::AMDOrdering<int>()(pattern, order);  // Computes A + Aᵀ's pattern itself.
    return {order.indices().data(), order.indices().data() + blocks};
}

// One stored block of the permuted upper triangle: new block row and column, and where
// its values are (H_ab as stored, or its transpose; nullptr for a diagonal block).
struct UpperBlock {
    int column = 0;
    int row = 0;
    const Matrix6d* block = nullptr;
    bool transposed = false;
};

std::vector<UpperBlock> upper_blocks(const BlockSystem& system, const std::vector<int>& position) {
    std::vector<UpperBlock> out;
    out.reserve(system.diagonal.size() + system.off_diagonal.size());
    for (std::size_t b = 0; b < system.diagonal.size(); ++b) {
        out.push_back({.column = position[b], .row = position[b]});
    }
    for (const auto& [ab, block] : system.off_diagonal) {
        const int pa = position[ab.first], pb = position[ab.second];
        out.push_back({.column = std::max(pa, pb),
                       .row = std::min(pa, pb),
                       .block = &block,
                       .transposed = pa > pb});
    }
    std::sort(out.begin(), out.end(), [](const UpperBlock& x, const UpperBlock& y) {
        return x.column != y.column ? x.column < y.column : x.row < y.row;
    });
    return out;
}

// Upper triangle of (H + λI) in the new block order, written column by column.
UpperMatrix upper_matrix(const BlockSystem& system, const std::vector<int>& order, double lambda) {
    const Eigen::Index n = 6 * static_cast<Eigen::Index>(order.size());
    std::vector<int> position(order.size());
    for (std::size_t p = 0; p < order.size(); ++p) position[order[p]] = static_cast<int>(p);
    const std::vector<UpperBlock> blocks = upper_blocks(system, position);
    UpperMatrix H(n, n);
    H.resizeNonZeros(
        static_cast<Eigen::Index>(21 * system.diagonal.size() + 36 * system.off_diagonal.size()));
    Eigen::Index nnz = 0;
    std::size_t first = 0;
    for (Eigen::Index B = 0; B < static_cast<Eigen::Index>(order.size()); ++B) {
        std::size_t last = first;
        while (last < blocks.size() && blocks[last].column == B) ++last;
        for (int c = 0; c < 6; ++c) {
            H.outerIndexPtr()[6 * B + c] = nnz;
            for (std::size_t k = first; k < last; ++k) {
                const UpperBlock& u = blocks[k];
                const Matrix6d& M = u.block ? *u.block : system.diagonal[order[B]];
                for (int r = 0; r < (u.block ? 6 : c + 1); ++r) {
                    H.innerIndexPtr()[nnz] = 6 * u.row + r;
                    H.valuePtr()[nnz++] =
                        (u.transposed ? M(c, r) : M(r, c)) + (!u.block && r == c ? lambda : 0.0);
                }
            }
        }
        first = last;
    }
    H.outerIndexPtr()[n] = nnz;
    return H;
}

Eigen::VectorXd solve_sparse(const BlockSystem& system, double lambda, double& ratio) {
    const std::vector<int> order = block_order(system);
    const UpperMatrix H = upper_matrix(system, order, lambda);
    const Eigen::SimplicialLDLT<UpperMatrix, Eigen::Upper, Eigen::NaturalOrdering<Eigen::Index>>
        ldlt(H);
    const Eigen::Index n = H.rows();
    if (ldlt.info() != Eigen::Success) {
        ratio = 0.0;
        return Eigen::VectorXd::Zero(n);
    }
    ratio = pivot_ratio(ldlt.vectorD());
    Eigen::VectorXd rhs(n);
    for (std::size_t p = 0; p < order.size(); ++p) {
        rhs.segment<6>(6 * static_cast<Eigen::Index>(p)) = -system.gradient[order[p]];
    }
    const Eigen::VectorXd permuted = ldlt.solve(rhs);
    Eigen::VectorXd u(n);
    for (std::size_t p = 0; p < order.size(); ++p) {
        u.segment<6>(6 * static_cast<Eigen::Index>(order[p])) =
            permuted.segment<6>(6 * static_cast<Eigen::Index>(p));
    }
    return u;
}

}  // namespace

bool usable(const FineCorrespondence& c) {
    return c.weight > 0.0 && std::isfinite(c.weight) && c.source_point_m.allFinite() &&
           c.target_point_m.allFinite() && c.target_normal.allFinite() &&
           c.target_normal.squaredNorm() > 0.5f;
}

std::size_t usable_count(const MultiviewLink& link) {
    return static_cast<std::size_t>(
        std::count_if(link.correspondences.begin(), link.correspondences.end(), usable));
}

double link_rms_m(const MultiviewLink& link, std::span<const Pose> T_world_scan) {
    double sum = 0.0;
    double weight = 0.0;
    for (const FineCorrespondence& c : link.correspondences) {
        if (!usable(c)) continue;
        const WorldCorrespondence w =
            to_world(c, T_world_scan[link.target_index], T_world_scan[link.source_index]);
        sum += c.weight * w.d * w.d;
        weight += c.weight;
    }
    return weight > 0.0 ? std::sqrt(sum / weight) : 0.0;
}

std::vector<bool> connected_scans(std::size_t scan_count, std::size_t fixed,
                                  std::span<const MultiviewLink> links,
                                  const std::vector<bool>& active) {
    std::vector<std::vector<std::size_t>> neighbours(scan_count);
    for (std::size_t l = 0; l < links.size(); ++l) {
        if (!active[l]) continue;
        neighbours[links[l].target_index].push_back(links[l].source_index);
        neighbours[links[l].source_index].push_back(links[l].target_index);
    }
    std::vector<bool> reached(scan_count, false);
    std::deque<std::size_t> queue{fixed};
    reached[fixed] = true;
    while (!queue.empty()) {
        const std::size_t s = queue.front();
        queue.pop_front();
        for (const std::size_t t : neighbours[s]) {
            if (!reached[t]) queue.push_back(t);
            reached[t] = true;
        }
    }
    return reached;
}

namespace {

/// Calls visit(scan, world point) for both ends of every usable correspondence of the
/// active links, in link order.
template <typename Visit>
void for_each_world_point(std::span<const Pose> T_world_scan, std::span<const MultiviewLink> links,
                          const std::vector<bool>& active, Visit&& visit) {
    for (std::size_t l = 0; l < links.size(); ++l) {
        if (!active[l]) continue;
        const MultiviewLink& link = links[l];
        for (const FineCorrespondence& c : link.correspondences) {
            if (!usable(c)) continue;
            visit(link.source_index, T_world_scan[link.source_index] * c.source_point_m);
            visit(link.target_index, T_world_scan[link.target_index] * c.target_point_m);
        }
    }
}

}  // namespace

// Two passes over the links (centroids, then spread) instead of a copy of every
// correspondence's world points (2 × 24 B a correspondence; docs/scan-registration.md,
// "Scale").
Parametrisation make_parametrisation(std::span<const Pose> T_world_scan,
                                     std::span<const MultiviewLink> links,
                                     const std::vector<bool>& active) {
    const std::size_t n = T_world_scan.size();
    std::vector<Eigen::Vector3d> sum(n, Eigen::Vector3d::Zero());
    std::vector<std::size_t> count(n, 0);
    for_each_world_point(T_world_scan, links, active, [&](std::size_t s, const Eigen::Vector3d& x) {
        sum[s] += x;
        ++count[s];
    });
    Parametrisation param;
    param.block.assign(n, -1);
    for (std::size_t s = 0; s < n; ++s) {
        param.reference_m.push_back(count[s] > 0 ? Eigen::Vector3d(sum[s] / double(count[s]))
                                                 : T_world_scan[s].translation());
    }
    std::vector<double> sum_sq(n, 0.0);
    for_each_world_point(T_world_scan, links, active, [&](std::size_t s, const Eigen::Vector3d& x) {
        sum_sq[s] += (x - param.reference_m[s]).squaredNorm();
    });
    double total_sq = 0.0;
    std::size_t total = 0;
    for (std::size_t s = 0; s < n; ++s) {
        total_sq += sum_sq[s];
        total += count[s];
    }
    const double length = total > 0 ? std::sqrt(total_sq / static_cast<double>(total)) : 0.0;
    param.length_m = length > 0.0 ? length : 1.0;
    return param;
}

void assign_blocks(Parametrisation& param, const std::vector<bool>& connected, std::size_t fixed) {
    param.block_count = 0;
    for (std::size_t s = 0; s < param.block.size(); ++s) {
        param.block[s] = (connected[s] && s != fixed) ? static_cast<int>(param.block_count++) : -1;
    }
}

BlockSystem assemble(std::span<const MultiviewLink> links, const std::vector<bool>& active,
                     std::span<const Pose> T_world_scan, const Parametrisation& param) {
    BlockSystem system;
    system.diagonal.assign(param.block_count, Matrix6d::Zero());
    system.gradient.assign(param.block_count, Vector6d::Zero());
    for (std::size_t l = 0; l < links.size(); ++l) {
        const int bk = param.block[links[l].source_index];
        const int bj = param.block[links[l].target_index];
        if (!active[l] || (bk < 0 && bj < 0)) continue;
        Eigen::Matrix<double, 12, 12> H = Eigen::Matrix<double, 12, 12>::Zero();
        Eigen::Matrix<double, 12, 1> g = Eigen::Matrix<double, 12, 1>::Zero();
        accumulate_link(links[l], T_world_scan, param, H, g);
        add_block(system, bk, bk, H.topLeftCorner<6, 6>());
        add_block(system, bj, bj, H.bottomRightCorner<6, 6>());
        add_block(system, bk, bj, H.topRightCorner<6, 6>());
        if (bk >= 0) system.gradient[bk] += g.head<6>();
        if (bj >= 0) system.gradient[bj] += g.tail<6>();
    }
    return system;
}

Steps solve(const BlockSystem& system, const MultiviewRefinementConfig& config) {
    Steps steps;
    if (system.diagonal.empty()) return steps;
    const double lambda = tikhonov(system, config.tikhonov_relative);
    const Eigen::VectorXd u = system.diagonal.size() <= config.max_dense_scans
                                  ? solve_dense(system, lambda, steps.pivot_ratio)
                                  : solve_sparse(system, lambda, steps.pivot_ratio);
    for (std::size_t s = 0; s < system.diagonal.size(); ++s) {
        steps.u.push_back(u.segment<6>(6 * s));
    }
    return steps;
}

std::pair<double, double> apply_steps(const Steps& steps, const Parametrisation& param,
                                      std::vector<Pose>& T_world_scan) {
    double max_rotation_rad = 0.0;
    double max_translation_m = 0.0;
    for (std::size_t s = 0; s < T_world_scan.size(); ++s) {
        if (param.block[s] < 0) continue;
        const Vector6d& u = steps.u[param.block[s]];
        const Twist twist{.angular_rad = u.head<3>() / param.length_m, .linear_m = u.tail<3>()};
        // Helical motion of v(x) = c̄' + c × (x - p): conjugate by the translation to p.
        const Pose motion = Eigen::Translation3d(param.reference_m[s]) * helical_motion(twist) *
                            Eigen::Translation3d(-param.reference_m[s]);
        T_world_scan[s] = orthonormalized(motion * T_world_scan[s]);
        max_rotation_rad = std::max(max_rotation_rad, twist.angular_rad.norm());
        max_translation_m = std::max(max_translation_m, twist.linear_m.norm());
    }
    return {max_rotation_rad, max_translation_m};
}

}  // namespace anascan::multiview_detail
