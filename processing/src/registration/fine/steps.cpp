#include "registration/fine/steps.hpp"

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>
#include <tbb/partitioner.h>

#include <Eigen/Eigenvalues>
#include <algorithm>
#include <cmath>
#include <numbers>
#include <unordered_map>

namespace anascan::fine_detail {
namespace {

// ---- Spread sampling ------------------------------------------------------------------

constexpr int kMaxVoxelTuningPasses = 4;

std::vector<std::uint32_t> finite_indices(std::span<const Eigen::Vector3f> points) {
    std::vector<std::uint32_t> out;
    out.reserve(points.size());
    for (std::size_t i = 0; i < points.size(); ++i) {
        if (points[i].allFinite()) out.push_back(static_cast<std::uint32_t>(i));
    }
    return out;
}

// Voxel coordinates relative to the bounds' minimum, packed 21 bits per axis.
struct VoxelKeyer {
    Eigen::Vector3f min_m;
    float inverse_size = 1.0f;

    std::uint64_t key(const Eigen::Vector3f& p) const {
        const Eigen::Vector3f v = (p - min_m) * inverse_size;
        const auto axis = [](float c) { return static_cast<std::uint64_t>(c) & 0x1FFFFFu; };
        return axis(v.x()) | (axis(v.y()) << 21) | (axis(v.z()) << 42);
    }
    Eigen::Vector3f centre(const Eigen::Vector3f& p) const {
        const Eigen::Vector3f v = ((p - min_m) * inverse_size).array().floor();
        return min_m + (v.array() + 0.5f).matrix() / inverse_size;
    }
};

// Occupied voxels, estimated from every `stride`-th point (tuning need not be exact).
std::size_t count_voxels(std::span<const Eigen::Vector3f> points,
                         std::span<const std::uint32_t> indices, const VoxelKeyer& keyer,
                         std::size_t stride) {
    std::unordered_map<std::uint64_t, std::uint32_t> occupied;
    occupied.reserve(indices.size() / stride + 1);
    for (std::size_t k = 0; k < indices.size(); k += stride) {
        occupied.emplace(keyer.key(points[indices[k]]), 0u);
    }
    return occupied.size();
}

// Tunes the voxel size so that about `count` voxels (at least `count` when reachable) are
// occupied: a surface occupies ~area / size² voxels, so scale the size by sqrt(ratio).
VoxelKeyer tune_voxels(std::span<const Eigen::Vector3f> points,
                       std::span<const std::uint32_t> indices, std::size_t count) {
    Eigen::Vector3f lo = points[indices.front()];
    Eigen::Vector3f hi = lo;
    for (std::uint32_t i : indices) {
        lo = lo.cwiseMin(points[i]);
        hi = hi.cwiseMax(points[i]);
    }
    const float extent = std::max((hi - lo).maxCoeff(), 1e-9f);
    float size = extent / std::sqrt(static_cast<float>(count));
    VoxelKeyer keyer{lo, 1.0f / size};
    const std::size_t stride = std::max<std::size_t>(1, indices.size() / (4 * count));
    for (int pass = 0; pass < kMaxVoxelTuningPasses; ++pass) {
        const double occupied = static_cast<double>(count_voxels(points, indices, keyer, stride));
        const double ratio = occupied / static_cast<double>(count);
        if (ratio >= 1.0 && ratio < 1.5) break;
        size *= static_cast<float>(std::sqrt(ratio) * (ratio < 1.0 ? 0.95 : 1.0));
        keyer.inverse_size = 1.0f / size;
    }
    return keyer;
}

// One point per occupied voxel (nearest its centre), then evenly thinned to `count`.
std::vector<std::uint32_t> voxel_pick(std::span<const Eigen::Vector3f> points,
                                      std::span<const std::uint32_t> indices, std::size_t count) {
    const VoxelKeyer keyer = tune_voxels(points, indices, count);
    std::unordered_map<std::uint64_t, std::uint32_t> slot_of_voxel;
    slot_of_voxel.reserve(indices.size());
    std::vector<std::uint32_t> picked;
    std::vector<float> picked_distance_sq;
    for (std::uint32_t i : indices) {
        const float d2 = (points[i] - keyer.centre(points[i])).squaredNorm();
        const auto [it, inserted] =
            slot_of_voxel.emplace(keyer.key(points[i]), static_cast<std::uint32_t>(picked.size()));
        if (inserted) {
            picked.push_back(i);
            picked_distance_sq.push_back(d2);
        } else if (d2 < picked_distance_sq[it->second]) {
            picked[it->second] = i;
            picked_distance_sq[it->second] = d2;
        }
    }
    if (picked.size() <= count) return picked;
    std::vector<std::uint32_t> thinned(count);
    for (std::size_t k = 0; k < count; ++k) thinned[k] = picked[k * picked.size() / count];
    return thinned;
}

Samples make_samples(const PointCloud& source, std::vector<std::uint32_t> chosen) {
    Samples s;
    s.indices = std::move(chosen);
    s.points.reserve(s.indices.size());
    Eigen::Vector3d sum = Eigen::Vector3d::Zero();
    for (std::uint32_t i : s.indices) {
        s.points.push_back(source.positions[i]);
        sum += source.positions[i].cast<double>();
    }
    if (source.has_normals()) {
        s.normals.reserve(s.indices.size());
        for (std::uint32_t i : s.indices) s.normals.push_back(source.normals[i]);
    }
    if (s.points.empty()) return s;
    s.centroid_m = sum / static_cast<double>(s.points.size());
    double spread_sq = 0.0;
    for (const Eigen::Vector3f& p : s.points) {
        spread_sq += (p.cast<double>() - s.centroid_m).squaredNorm();
    }
    s.length_m = std::max(std::sqrt(spread_sq / static_cast<double>(s.points.size())), 1e-9);
    return s;
}

// ---- Correspondences and normal equations ---------------------------------------------

// The current pose and linearisation point of one pass, in target local coordinates.
struct PassFrame {
    Eigen::Matrix3d R;
    Eigen::Vector3d t;
    Eigen::Vector3d centroid_m;  // Samples' centroid moved by the current pose.
    double inverse_length = 1.0;
};

float kernel_weight(RobustKernel kernel, double width_m, double residual_m) {
    const double a = std::abs(residual_m);
    switch (kernel) {
        case RobustKernel::kNone:
            return 1.0f;
        case RobustKernel::kHuber:
            return a <= width_m ? 1.0f : static_cast<float>(width_m / a);
        case RobustKernel::kTukey: {
            if (a >= width_m) return 0.0f;
            const double u = 1.0 - (a / width_m) * (a / width_m);
            return static_cast<float>(u * u);
        }
    }
    return 0.0f;
}

// Eq. 2 for one inlier: residual r + v(x)·n with v(x)·n = c̄'·n + c·((x - m) × n).
void accumulate_one(const Eigen::Vector3d& x, const Eigen::Vector3d& n, const Match& match,
                    const PassFrame& frame, Accumulation& acc) {
    Vector6d J;
    J.head<3>() = (x - frame.centroid_m).cross(n) * frame.inverse_length;
    J.tail<3>() = n;
    const double w = match.weight;
    const double r = match.residual_m;
    acc.H.noalias() += (w * J) * J.transpose();
    acc.g.noalias() += (w * r) * J;
    acc.residual_sq_sum += r * r;
    acc.point_distance_sq_sum += match.distance_sq_m2;
    ++acc.inliers;
}

// The plane normal of a correspondence: the target's, or in the symmetric form the mean of
// the (moved) source normal and the target's when they face the same way (Rusinkiewicz
// 2019: the optimum is not biased toward the target's side of the surface).
Eigen::Vector3d plane_normal(const Samples& samples, std::size_t i, const PassFrame& frame,
                             const Eigen::Vector3d& n_target, const MatchSettings& settings) {
    if (!settings.symmetric || samples.normals.empty()) return n_target;
    const Eigen::Vector3d n_source = frame.R * samples.normals[i].cast<double>();
    const Eigen::Vector3d sum = n_source + n_target;
    if (!(n_source.dot(n_target) > 0.0) || !sum.allFinite()) return n_target;
    return sum.normalized();
}

Accumulation match_chunk(const Samples& samples, const TargetView& target,
                         const MatchSettings& settings, const PassFrame& frame, std::size_t begin,
                         std::size_t end, std::span<Match> matches) {
    Accumulation acc;
    const double gate_sq = settings.gate_m * settings.gate_m;
    // A hair above the bound, so float rounding never drops a match the double gate keeps.
    const auto bound_m = static_cast<float>(settings.search_bound_m * 1.001);
    for (std::size_t i = begin; i < end; ++i) {
        Match& match = matches[i];
        match = Match{};
        const Eigen::Vector3d x = frame.R * samples.points[i].cast<double>() + frame.t;
        Neighbor nb;
        if (!target.tree->nearest_within(x.cast<float>(), bound_m, nb)) continue;
        const Eigen::Vector3d n_target = target.normals[nb.index].cast<double>();
        if (!n_target.allFinite()) continue;
        const Eigen::Vector3d n = plane_normal(samples, i, frame, n_target, settings);
        const Eigen::Vector3d d = x - target.points[nb.index].cast<double>();
        match.target_index = nb.index;
        match.distance_sq_m2 = static_cast<float>(d.squaredNorm());
        match.residual_m = static_cast<float>(d.dot(n));
        if (d.squaredNorm() > gate_sq) continue;
        if (!samples.normals.empty() &&
            (frame.R * samples.normals[i].cast<double>()).dot(n_target) < settings.min_normal_cos) {
            continue;
        }
        match.weight = kernel_weight(settings.kernel, settings.kernel_width_m, d.dot(n));
        if (match.weight > 0.0f) accumulate_one(x, n, match, frame, acc);
    }
    return acc;
}

}  // namespace

Samples sample_spread(const PointCloud& source, std::size_t count) {
    std::vector<std::uint32_t> finite = finite_indices(source.positions);
    if (finite.size() > count && count > 0) {
        finite = voxel_pick(source.positions, finite, count);
    }
    return make_samples(source, std::move(finite));
}

MatchSettings match_settings(const FineRegistrationConfig& config, double gate_m, bool symmetric) {
    const double cos_limit = std::cos(config.max_normal_angle_deg * std::numbers::pi / 180.0);
    return {.gate_m = gate_m,
            .search_bound_m = std::max(gate_m, config.overlap_distance_m),
            .kernel = config.robust_kernel,
            .kernel_width_m = config.robust_width_fraction * gate_m,
            .min_normal_cos = cos_limit,
            .chunk_size = config.chunk_size,
            .symmetric = symmetric};
}

Accumulation& Accumulation::operator+=(const Accumulation& other) {
    H += other.H;
    g += other.g;
    residual_sq_sum += other.residual_sq_sum;
    point_distance_sq_sum += other.point_distance_sq_sum;
    inliers += other.inliers;
    return *this;
}

Accumulation match_and_accumulate(const Samples& samples, const TargetView& target,
                                  const Pose& T_local, const MatchSettings& settings,
                                  std::span<Match> matches, std::vector<Accumulation>& chunk_sums) {
    const std::size_t n = samples.points.size();
    const std::size_t chunk = std::max<std::size_t>(settings.chunk_size, 1);
    const std::size_t chunks = (n + chunk - 1) / chunk;
    chunk_sums.resize(chunks);
    const PassFrame frame{T_local.linear(), T_local.translation(), T_local * samples.centroid_m,
                          1.0 / samples.length_m};
    tbb::parallel_for(
        tbb::blocked_range<std::size_t>(0, chunks, 1),
        [&](const tbb::blocked_range<std::size_t>& range) {
            for (std::size_t c = range.begin(); c != range.end(); ++c) {
                chunk_sums[c] = match_chunk(samples, target, settings, frame, c * chunk,
                                            std::min(n, (c + 1) * chunk), matches);
            }
        },
        tbb::simple_partitioner());
    Accumulation total;
    for (const Accumulation& part : chunk_sums) total += part;  // Fixed order.
    return total;
}

DegeneracyFigure measure_degeneracy(const Matrix6d& H, double length_m) {
    DegeneracyFigure figure;
    figure.characteristic_length_m = length_m;
    const Eigen::SelfAdjointEigenSolver<Matrix6d> eigen(H);
    const Vector6d lambda = eigen.eigenvalues();  // Ascending.
    figure.eigenvalue_ratio = lambda(5) > 0.0 ? std::max(lambda(0), 0.0) / lambda(5) : 0.0;
    Vector6d weakest = eigen.eigenvectors().col(0);
    Eigen::Index largest = 0;
    weakest.cwiseAbs().maxCoeff(&largest);
    if (weakest(largest) < 0.0) weakest = -weakest;  // A reproducible sign.
    figure.weakest_direction = weakest;
    return figure;
}

Twist solve_step(const Accumulation& sums, const DegeneracyFigure& degeneracy,
                 double degeneracy_threshold, double length_m, const Eigen::Vector3d& centroid_m) {
    Vector6d xi = Vector6d::Zero();
    if (degeneracy.eigenvalue_ratio >= degeneracy_threshold) {
        xi = sums.H.ldlt().solve(-sums.g);
    } else {
        // Rank-limited: move only along the directions the constraint fixes.
        const Eigen::SelfAdjointEigenSolver<Matrix6d> eigen(sums.H);
        const double floor = degeneracy_threshold * eigen.eigenvalues()(5);
        for (int k = 0; k < 6; ++k) {
            const double lambda = eigen.eigenvalues()(k);
            if (lambda <= floor || lambda <= 0.0) continue;
            const Vector6d v = eigen.eigenvectors().col(k);
            xi -= v * (v.dot(sums.g) / lambda);
        }
    }
    const Twist about_centroid{xi.head<3>() / length_m, xi.tail<3>()};
    return twist_about_origin(about_centroid, centroid_m);
}

}  // namespace anascan::fine_detail
