// The lengths of a live session from the device's spacing and noise.
#include "anascan/acquisition/live/device_scale.hpp"

#include <Eigen/Eigenvalues>
#include <algorithm>
#include <cmath>
#include <vector>

#include "anascan/processing/core/median.hpp"
#include "anascan/processing/spatial/kdtree.hpp"

namespace anascan::acquisition {
namespace {

/// Neighbours are found in 3-D, so where the noise is as large as the spacing (a terrestrial
/// scanner: 7 mm at 6-7 mm) the nearest ones are those at the point's own height, and a small
/// neighbourhood's plane follows the point: 16 neighbours measured 3.8 mm of a plane's 7 mm
/// noise at 6 mm spacing, 64 neighbours (a radius of 4 noises) 5.9 mm.
constexpr std::size_t kNeighbourhood = 64;

/// Distance of the first neighbour (the point itself) to the least-squares plane of the
/// others: left out of the fit, the point's residual keeps its whole noise (a plane fitted
/// through it absorbs a part of it where the spacing is as large as the noise).
double residual_off_neighbours(const PointCloud& cloud, const std::vector<Neighbor>& near) {
    Eigen::Vector3d mean = Eigen::Vector3d::Zero();
    for (std::size_t k = 1; k < near.size(); ++k)
        mean += cloud.positions[near[k].index].cast<double>();
    mean /= static_cast<double>(near.size() - 1);
    Eigen::Matrix3d covariance = Eigen::Matrix3d::Zero();
    for (std::size_t k = 1; k < near.size(); ++k) {
        const Eigen::Vector3d d = cloud.positions[near[k].index].cast<double>() - mean;
        covariance += d * d.transpose();
    }
    const Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> eigen(covariance);
    const Eigen::Vector3d normal = eigen.eigenvectors().col(0);
    return std::abs(normal.dot(cloud.positions[near[0].index].cast<double>() - mean));
}

void raise_to(double& length_m, double bound_m) { length_m = std::max(length_m, bound_m); }

}  // namespace

DeviceScale measure_device_scale(const PointCloud& cloud, std::size_t max_samples) {
    DeviceScale out;
    std::vector<std::size_t> finite;
    finite.reserve(cloud.size());
    for (std::size_t i = 0; i < cloud.size(); ++i)
        if (cloud.positions[i].allFinite()) finite.push_back(i);
    if (finite.size() < kNeighbourhood) return out;
    const PointCloud points = finite.size() == cloud.size() ? cloud : select(cloud, finite);
    const KdTree tree(points.positions);
    const std::size_t stride = std::max<std::size_t>(1, points.size() / max_samples);
    std::vector<double> spacing, noise;
    std::vector<Neighbor> near;
    for (std::size_t i = 0; i < points.size(); i += stride) {
        tree.knn(points.positions[i], kNeighbourhood, near);
        if (near.size() < kNeighbourhood) continue;
        spacing.push_back((points.positions[near[1].index] - points.positions[i]).norm());
        noise.push_back(residual_off_neighbours(points, near));
    }
    out.samples = spacing.size();
    if (out.samples == 0) return out;
    out.spacing_m = upper_median(spacing);
    // Median |residual| of a Gaussian is 0.6745 sigma; the neighbours' plane adds its own
    // error (about sigma / sqrt(63) at the point).
    out.noise_m = upper_median(noise) / 0.6745 / std::sqrt(1.0 + 1.0 / (kNeighbourhood - 1));
    return out;
}

LiveRegistrationConfig lengths_for_device(LiveRegistrationConfig c, const DeviceScale& scale) {
    const double n = scale.noise_m;
    if (!(n > 0.0)) return c;
    // A voxel of three noises: a normal's neighbourhood (15 points) is wider than the noise,
    // and the RMS limit (0.75 voxel) is 2.25 noises, where two independent noisy surfaces
    // fit at about 1.6 (sim:tof: 5.7-5.9 mm at 3.6 mm measured noise).
    raise_to(c.prepare.voxel_size_m, 3.0 * n);
    raise_to(c.prepare.ground.distance_threshold_m, 2.0 * n);
    raise_to(c.prepare.ground_band_m, 3.0 * n);
    // Fine registration: correspondences within three noises are the surface's, the first
    // gate covers a prediction's error and ten noises.
    for (FineRegistrationConfig* fine :
         {&c.hypotheses.fine, &c.links.fine, &c.global.registration.fine}) {
        raise_to(fine->min_correspondence_distance_m, 3.0 * n);
        raise_to(fine->max_correspondence_distance_m, fine == &c.links.fine ? 4.0 * n : 10.0 * n);
        raise_to(fine->overlap_distance_m, 3.0 * n);
    }
    raise_to(c.verify.min_rms_limit_m, n);
    raise_to(c.votes.displacement_m, 2.0 * n);
    raise_to(c.global.registration.matching.distance_tolerance_m, n);
    raise_to(c.global.registration.matching.distinct_translation_m, 2.0 * n);
    return c;
}

}  // namespace anascan::acquisition
