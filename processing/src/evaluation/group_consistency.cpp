// check_group_consistency: every overlapping pair of a group tested for crossing normals,
// free space and the angle of its overlap, at thresholds from the scans' own sampling.
#include "anascan/processing/evaluation/group_consistency.hpp"

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <memory>
#include <numbers>
#include <vector>

#include "anascan/processing/features/integral_invariants.hpp"
#include "anascan/processing/spatial/kdtree.hpp"

namespace anascan {
namespace {

constexpr double kDeg = 180.0 / std::numbers::pi;
/// median |n·(q - p)| of two neighbours with independent normal noise σ is 0.954 σ.
constexpr double kMedianAbsOfDifference = 0.954;

double median_of(std::vector<double> values) {
    if (values.empty()) return 0.0;
    auto middle = values.begin() + static_cast<std::ptrdiff_t>(values.size() / 2);
    std::nth_element(values.begin(), middle, values.end());
    return *middle;
}

bool usable_normal(const PointCloud& cloud, std::size_t i) {
    return cloud.has_normals() && cloud.normals[i].squaredNorm() > 0.5f;
}

/// Angle between two unit normals, sign ignored, degrees.
double unsigned_angle_deg(const Eigen::Vector3f& n, const Eigen::Vector3f& m) {
    return std::acos(std::clamp(static_cast<double>(std::abs(n.dot(m))), 0.0, 1.0)) * kDeg;
}

/// A scan with what the tests need of it: tree, sampling figures, bounds in the group frame.
struct Prepared {
    const ConsistencyScan* scan = nullptr;
    std::unique_ptr<KdTree> tree;
    double spacing_m = 0.0, noise_m = 0.0, normal_noise_deg = 0.0;
    Eigen::Vector3d centre_m = Eigen::Vector3d::Zero();  ///< Group frame.
    double radius_m = 0.0;
};

/// Noise along the normal and normal noise, from each sampled point's nearest neighbour.
void measure_noise(const PointCloud& cloud, const KdTree& tree, std::size_t max_samples,
                   Prepared& out) {
    std::vector<double> offsets, angles;
    std::vector<Neighbor> nearest;
    const std::size_t stride = std::max<std::size_t>(1, cloud.size() / max_samples);
    for (std::size_t i = 0; i < cloud.size(); i += stride) {
        if (!usable_normal(cloud, i)) continue;
        tree.knn(cloud.positions[i], 2, nearest);
        if (nearest.size() < 2 || !usable_normal(cloud, nearest[1].index)) continue;
        const std::uint32_t j = nearest[1].index;
        offsets.push_back(std::abs(cloud.normals[i].dot(cloud.positions[j] - cloud.positions[i])));
        angles.push_back(unsigned_angle_deg(cloud.normals[i], cloud.normals[j]));
    }
    if (!(out.noise_m > 0.0)) out.noise_m = median_of(offsets) / kMedianAbsOfDifference;
    out.normal_noise_deg = median_of(angles);
}

Prepared prepare(const ConsistencyScan& scan, const GroupConsistencyConfig& config) {
    Prepared p{.scan = &scan, .spacing_m = scan.spacing_m, .noise_m = scan.noise_m};
    const PointCloud& cloud = *scan.cloud;
    p.tree = std::make_unique<KdTree>(cloud.positions);
    if (!(p.spacing_m > 0.0)) p.spacing_m = median_sample_spacing_m(cloud);
    measure_noise(cloud, *p.tree, config.max_samples, p);
    if (cloud.empty()) return p;
    const Bounds b = local_bounds(cloud);
    const Eigen::Vector3d local_centre = 0.5 * (b.min + b.max).cast<double>();
    p.centre_m = scan.T_group_scan * (cloud.origin_m + local_centre);
    p.radius_m = 0.5 * b.extent().cast<double>().norm();
    return p;
}

/// Near points of `from` on `onto`'s surface: normal angles and offsets appended.
std::size_t near_points(const Prepared& from, const Prepared& onto, double near_m,
                        const GroupConsistencyConfig& config, std::vector<double>& angles,
                        std::vector<double>& offsets) {
    const PointCloud& a = *from.scan->cloud;
    const PointCloud& b = *onto.scan->cloud;
    const Eigen::Isometry3f T_local =
        (Eigen::Translation3d(-b.origin_m) * onto.scan->T_group_scan.inverse() *
         from.scan->T_group_scan * Eigen::Translation3d(a.origin_m))
            .cast<float>();
    const Eigen::Matrix3f R = T_local.linear();
    const std::size_t stride = std::max<std::size_t>(1, a.size() / config.max_samples);
    Neighbor nearest;
    std::size_t examined = 0;
    for (std::size_t i = 0; i < a.size(); i += stride) {
        if (!usable_normal(a, i)) continue;
        ++examined;
        if (!onto.tree->nearest_within(T_local * a.positions[i], static_cast<float>(near_m),
                                       nearest) ||
            !usable_normal(b, nearest.index))
            continue;
        const Eigen::Vector3f& n = b.normals[nearest.index];
        const Eigen::Vector3f q = T_local * a.positions[i];
        angles.push_back(unsigned_angle_deg(R * a.normals[i], n));
        offsets.push_back(std::abs(n.dot(q - b.positions[nearest.index])));
    }
    return examined;
}

/// `other`'s points against `viewed`'s view from its sensor (invalid without a sensor).
FreeSpaceResult free_space(const Prepared& viewed, const Prepared& other,
                           const GroupConsistencyConfig& config) {
    if (!viewed.scan->sensor_origin_scan_m || !(viewed.spacing_m > 0.0)) return {};
    FreeSpaceConfig fs = config.free_space;
    const double noisy =
        config.free_space_noise_factor * std::max(viewed.noise_m, other.noise_m) / viewed.spacing_m;
    fs.tolerance_spacing_factor = std::max(fs.tolerance_spacing_factor, noisy);
    const Pose T_viewed_other = viewed.scan->T_group_scan.inverse() * other.scan->T_group_scan;
    return check_free_space(*viewed.scan->cloud, *viewed.scan->sensor_origin_scan_m,
                            viewed.spacing_m, *other.scan->cloud, T_viewed_other, fs);
}

bool violated(const FreeSpaceResult& r, const FreeSpaceConfig& config) {
    return r.valid && r.in_view >= config.min_points_in_view &&
           r.violation_fraction > config.max_violation_fraction;
}

bool has_evidence(const PairConsistency& p, const GroupConsistencyConfig& config) {
    const std::size_t view = config.free_space.min_points_in_view;
    return p.near_samples >= config.min_near_samples || p.b_seen_from_a.in_view >= view ||
           p.a_seen_from_b.in_view >= view;
}

/// Free space, then the angle of the overlap (its near points mostly cross: surfaces that
/// cut through each other meet only along a line, so their count is not asked for), then,
/// for an overlap of enough of the points examined, crossing normals and the offset.
void judge(PairConsistency& p, std::size_t examined, const GroupConsistencyConfig& config) {
    const bool counted = p.near_samples >= config.min_near_samples;
    const bool overlap = counted && static_cast<double>(p.near_samples) >=
                                        config.min_near_fraction * static_cast<double>(examined);
    if (violated(p.b_seen_from_a, config.free_space) ||
        violated(p.a_seen_from_b, config.free_space)) {
        p.agrees = false;
        p.reason = "free space";
    } else if (counted && p.median_normal_angle_deg > p.crossing_angle_deg) {
        p.agrees = false;
        p.reason = "angle";
    } else if (overlap && p.crossing_fraction > config.max_crossing_fraction) {
        p.agrees = false;
        p.reason = "normals cross";
    } else if (overlap && config.max_offset_noise_factor > 0.0 && p.noise_m > 0.0 &&
               p.median_offset_m > config.max_offset_noise_factor * p.noise_m) {
        p.agrees = false;
        p.reason = "surfaces apart";
    }
}

PairConsistency check_prepared(const Prepared& a, const Prepared& b,
                               const GroupConsistencyConfig& config) {
    PairConsistency p;
    const double spacing = std::max(a.spacing_m, b.spacing_m);
    const double noise = std::max(a.noise_m, b.noise_m);
    const double near_m = config.near_spacing_factor * spacing + config.near_noise_factor * noise;
    p.crossing_angle_deg =
        std::max(config.min_crossing_angle_deg,
                 config.crossing_noise_factor * std::max(a.normal_noise_deg, b.normal_noise_deg));
    p.noise_m = std::sqrt(0.5 * (a.noise_m * a.noise_m + b.noise_m * b.noise_m));
    std::vector<double> angles, offsets;
    const std::size_t examined = near_points(a, b, near_m, config, angles, offsets) +
                                 near_points(b, a, near_m, config, angles, offsets);
    p.median_offset_m = median_of(std::move(offsets));
    p.near_samples = angles.size();
    const auto crossing = std::count_if(angles.begin(), angles.end(),
                                        [&](double deg) { return deg > p.crossing_angle_deg; });
    if (!angles.empty())
        p.crossing_fraction = static_cast<double>(crossing) / static_cast<double>(angles.size());
    p.median_normal_angle_deg = median_of(std::move(angles));
    p.b_seen_from_a = free_space(a, b, config);
    p.a_seen_from_b = free_space(b, a, config);
    judge(p, examined, config);
    return p;
}

}  // namespace

PairConsistency check_pair_consistency(const ConsistencyScan& a, const ConsistencyScan& b,
                                       const GroupConsistencyConfig& config) {
    if (!a.cloud || !b.cloud || a.cloud->empty() || b.cloud->empty()) return {.a = 0, .b = 1};
    PairConsistency p = check_prepared(prepare(a, config), prepare(b, config), config);
    p.a = 0;
    p.b = 1;
    return p;
}

GroupConsistency check_group_consistency(std::span<const ConsistencyScan> scans,
                                         const GroupConsistencyConfig& config) {
    GroupConsistency group;
    group.scans.resize(scans.size());
    std::vector<Prepared> prepared;
    prepared.reserve(scans.size());
    for (const ConsistencyScan& s : scans) prepared.push_back(prepare(s, config));
    for (std::size_t j = 0; j < scans.size(); ++j) {
        for (std::size_t i = 0; i < j; ++i) {
            const Prepared &a = prepared[i], &b = prepared[j];
            if (!scans[i].cloud || !scans[j].cloud || scans[i].cloud->empty() ||
                scans[j].cloud->empty() ||
                (a.centre_m - b.centre_m).norm() > a.radius_m + b.radius_m)
                continue;
            PairConsistency p = check_prepared(a, b, config);
            if (!has_evidence(p, config)) continue;
            p.a = i;
            p.b = j;
            group.pairs.push_back(std::move(p));
        }
    }
    choose_take_out(group);
    return group;
}

}  // namespace anascan
