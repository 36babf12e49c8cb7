// The campaign's global descriptor of a scan: hashed triangles of its integral-invariant
// keypoints, free of pose and of the scan's size.
//
// Sites are placed densely (about one per sample spacing) and the keypoints are the extrema
// of V_r (`invariant_keypoints`), so that they follow the surface, not a grid of the scan's
// frame. A triangle joins a keypoint and two of its nearest keypoints of the same radius; its key
// holds per side a log-scale length bin and the kind (absolute radius level, side) of the opposite
// corner, in sorted order. Two overlapping scans share the triangles of their common part;
// unrelated scans share only what chance gives.
#include <Eigen/Eigenvalues>
#include <algorithm>
#include <array>
#include <cmath>
#include <string>
#include <utility>

#include "anascan/processing/campaign/campaign_stages.hpp"
#include "anascan/processing/features/integral_invariants.hpp"
#include "anascan/processing/features/invariant_keypoints.hpp"

namespace anascan {
namespace {

constexpr double kLadderRatio = 1.5;    // Radii ladder shared by the campaign (= geometric).
constexpr double kLadderUnit_m = 1e-3;  // Ladder level 0.

struct Ladder {
    InvariantRadii radii_m{};
    int first_level = 0;  ///< Absolute level of radii_m[0].
};

Ladder ladder_for(double diagonal_m) {
    const double r0 = radii_for_object_size_m(diagonal_m)[0];
    const int level =
        static_cast<int>(std::lround(std::log(r0 / kLadderUnit_m) / std::log(kLadderRatio)));
    return {.radii_m = geometric_radii_m(kLadderUnit_m * std::pow(kLadderRatio, level)),
            .first_level = level};
}

std::uint64_t corner_kind(const InvariantKeypoint& p, int first_level) {
    const auto level =
        static_cast<std::uint64_t>(first_level + 64 + static_cast<int>(p.radius_index));
    return (level << 1) | static_cast<std::uint64_t>(p.side);
}

struct KeyContext {
    const std::vector<InvariantKeypoint>& corners;
    int first_level = 0;
    double log_ratio = 0.0;
};

double distance_m(const KeyContext& c, std::size_t a, std::size_t b) {
    return (c.corners[a].position_m - c.corners[b].position_m).norm();
}

// Keys of triangle (a, b, c): per side its bin and the nearer neighbouring bin (2^3 keys).
void triangle_keys(const KeyContext& c, const std::array<std::size_t, 3>& corner,
                   std::vector<std::uint64_t>& keys) {
    std::array<std::array<std::uint64_t, 2>, 3> bins{};
    for (std::size_t k = 0; k < 3; ++k) {
        const double length_m = distance_m(c, corner[(k + 1) % 3], corner[(k + 2) % 3]);
        const double x = std::log(length_m / kLadderUnit_m) / c.log_ratio + 64.0;
        const auto bin = static_cast<std::uint64_t>(std::max(x, 1.0));
        const bool upper = x - static_cast<double>(bin) >= 0.5;
        bins[k] = {bin, upper ? bin + 1 : bin - 1};
    }
    for (unsigned combo = 0; combo < 8; ++combo) {
        std::array<std::uint64_t, 3> t{};
        for (std::size_t k = 0; k < 3; ++k) {
            t[k] = (bins[k][(combo >> k) & 1u] & 0x7ff) << 10 |
                   corner_kind(c.corners[corner[k]], c.first_level);
        }
        std::sort(t.begin(), t.end());
        keys.push_back(t[0] << 42 | t[1] << 21 | t[2]);
    }
}

// Keypoint a's nearest keypoints of its radius within [min_side_m, max_side_m].
std::vector<std::size_t> partners(const KeyContext& c, std::size_t a, double min_side_m,
                                  double max_side_m, std::size_t count) {
    std::vector<std::pair<double, std::size_t>> near;
    for (std::size_t b = 0; b < c.corners.size(); ++b) {
        const double d = distance_m(c, a, b);
        if (b != a && c.corners[b].radius_index == c.corners[a].radius_index && d <= max_side_m &&
            d >= min_side_m) {
            near.emplace_back(d, b);
        }
    }
    const std::size_t keep = std::min(count, near.size());
    std::partial_sort(near.begin(), near.begin() + static_cast<std::ptrdiff_t>(keep), near.end());
    std::vector<std::size_t> out;
    for (std::size_t i = 0; i < keep; ++i) out.push_back(near[i].second);
    return out;
}

std::vector<std::uint64_t> feature_keys(const KeyContext& c, double min_side_m, double max_side_m,
                                        std::size_t nearest) {
    std::vector<std::uint64_t> keys;
    for (std::size_t a = 0; a < c.corners.size(); ++a) {
        const std::vector<std::size_t> near = partners(c, a, min_side_m, max_side_m, nearest);
        for (std::size_t i = 0; i < near.size(); ++i) {
            for (std::size_t j = i + 1; j < near.size(); ++j) {
                const double bc = distance_m(c, near[i], near[j]);
                if (bc > max_side_m || bc < min_side_m) continue;
                triangle_keys(c, {a, near[i], near[j]}, keys);
            }
        }
    }
    std::sort(keys.begin(), keys.end());
    keys.erase(std::unique(keys.begin(), keys.end()), keys.end());
    return keys;
}

/// A size that does not depend on the frame (a bounding box's diagonal does): 2.5 times the
/// RMS distance from the centroid (a box's diagonal for a cube's six faces seen whole).
double rotation_free_size_m(const PointCloud& cloud) {
    if (cloud.empty()) return 0.0;
    Eigen::Vector3d mean = Eigen::Vector3d::Zero();
    for (const Eigen::Vector3f& p : cloud.positions) mean += p.cast<double>();
    mean /= static_cast<double>(cloud.size());
    double sum_sq = 0.0;
    for (const Eigen::Vector3f& p : cloud.positions)
        sum_sq += (p.cast<double>() - mean).squaredNorm();
    return 2.5 * std::sqrt(sum_sq / static_cast<double>(cloud.size()));
}

/// RMS distance of the points from their best-fit plane (the smallest principal axis).
double plane_rms_m(const PointCloud& cloud) {
    if (cloud.size() < 3) return 0.0;
    Eigen::Vector3d mean = Eigen::Vector3d::Zero();
    for (const Eigen::Vector3f& p : cloud.positions) mean += p.cast<double>();
    mean /= static_cast<double>(cloud.size());
    Eigen::Matrix3d covariance = Eigen::Matrix3d::Zero();
    for (const Eigen::Vector3f& p : cloud.positions) {
        const Eigen::Vector3d d = p.cast<double>() - mean;
        covariance += d * d.transpose();
    }
    covariance /= static_cast<double>(cloud.size());
    const Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> solver(covariance);
    return std::sqrt(std::max(0.0, solver.eigenvalues()[0]));
}

}  // namespace

ScanDescriptor describe_campaign_scan(const PointCloud& prepared, double spacing_m,
                                      const CampaignConfig& config) {
    ScanDescriptor out;
    // Relief below half a sample spacing is a plane at the scale the scan was sampled: no key
    // can tell one part of it from another (the ground, a wall, a sawn face seen alone); the
    // keypoints such relief gives are noise.
    if (const double rms_m = plane_rms_m(prepared);
        prepared.size() >= 3 && rms_m < 0.5 * spacing_m) {
        out.problem = "within " + std::to_string(rms_m * 1e3).substr(0, 4) +
                      " mm (RMS) of one plane, less than half its " +
                      std::to_string(spacing_m * 1e3).substr(0, 4) +
                      " mm sample spacing: a featureless surface (a plane, the ground or "
                      "background only?)";
        return out;
    }
    const double diagonal_m = rotation_free_size_m(prepared);
    const Ladder ladder = ladder_for(diagonal_m);
    IntegralInvariantConfig invariant_config = config.registration.global.invariants;
    invariant_config.radii_m = ladder.radii_m;
    invariant_config.site_spacing_m =
        std::max(config.key_site_spacing_factor * spacing_m,
                 config.key_site_spacing_radius_fraction * ladder.radii_m[0]);
    invariant_config.frame_free_sampling = true;
    const IntegralInvariantResult invariants =
        compute_integral_invariants(prepared, invariant_config);
    if (invariants.status != IntegralInvariantStatus::kOk) {
        out.problem = "no valid integral-invariant descriptor (too few points or no interior)";
        return out;
    }
    const std::vector<InvariantKeypoint> keypoints =
        invariant_keypoints(invariants, config.keypoints);
    out.keypoints = keypoints.size();
    const KeyContext context{.corners = keypoints,
                             .first_level = ladder.first_level,
                             .log_ratio = std::log(config.key_length_ratio)};
    out.keys = feature_keys(context, 2.0 * ladder.radii_m[0], 0.25 * diagonal_m,
                            config.key_nearest_keypoints);
    if (out.keys.empty()) {
        out.problem = std::to_string(keypoints.size()) +
                      " keypoints and no keypoint triangle: a featureless surface (a plane, "
                      "the ground or background only?)";
    }
    return out;
}

}  // namespace anascan
