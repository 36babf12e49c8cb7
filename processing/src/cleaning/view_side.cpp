// The side a range scan was seen from: the normals' dominant axis, its end by convexity.
#include "anascan/processing/cleaning/view_side.hpp"

#include <Eigen/Eigenvalues>
#include <cmath>

namespace anascan {
namespace {

/// Eigenvector of the largest eigenvalue of Σ n nᵀ (sign arbitrary); empty sum: +z.
Eigen::Vector3d normal_axis(const PointCloud& cloud, std::size_t& nonzero) {
    Eigen::Matrix3d scatter = Eigen::Matrix3d::Zero();
    nonzero = 0;
    for (const Eigen::Vector3f& n : cloud.normals) {
        if (n.isZero() || !n.allFinite()) continue;
        const Eigen::Vector3d d = n.cast<double>();
        scatter += d * d.transpose();
        ++nonzero;
    }
    if (nonzero == 0) return Eigen::Vector3d::UnitZ();
    const Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> solver(scatter);
    return solver.eigenvectors().col(2);
}

/// Mean n·(p − c) over the mean |p − c| of the non-zero normals.
double convexity(const PointCloud& cloud) {
    Eigen::Vector3d centroid = Eigen::Vector3d::Zero();
    for (const Eigen::Vector3f& p : cloud.positions) centroid += p.cast<double>();
    centroid /= static_cast<double>(cloud.size());
    double outward = 0.0, spread = 0.0;
    for (std::size_t i = 0; i < cloud.size(); ++i) {
        const Eigen::Vector3f& n = cloud.normals[i];
        if (n.isZero() || !n.allFinite()) continue;
        const Eigen::Vector3d d = cloud.positions[i].cast<double>() - centroid;
        outward += n.cast<double>().dot(d);
        spread += d.norm();
    }
    return spread > 0.0 ? outward / spread : 0.0;
}

}  // namespace

ViewSideResult orient_as_range_scan(PointCloud& cloud, const ViewSideConfig& config) {
    ViewSideResult result;
    if (cloud.normals.size() != cloud.size() || cloud.empty()) return result;
    std::size_t nonzero = 0;
    Eigen::Vector3f axis = normal_axis(cloud, nonzero).cast<float>();
    if (nonzero == 0) return result;
    std::size_t facing = 0;
    const std::vector<Eigen::Vector3f> before = cloud.normals;
    for (Eigen::Vector3f& n : cloud.normals) {
        if (n.isZero() || !n.allFinite()) continue;
        const float along = n.dot(axis);
        facing += std::abs(along) > 0.1f;
        if (along < 0.0f) n = -n;
    }
    result.convexity = convexity(cloud);
    result.decided = std::abs(result.convexity) >= config.min_convexity_fraction;
    const bool flip = result.decided ? result.convexity < 0.0 : axis.z() < 0.0f;
    if (flip) {
        for (Eigen::Vector3f& n : cloud.normals) n = -n;
        axis = -axis;
        result.convexity = -result.convexity;
    }
    for (std::size_t i = 0; i < cloud.size(); ++i) {
        result.num_flipped += cloud.normals[i].dot(before[i]) < 0.0f;
    }
    result.oriented = true;
    result.view_direction = axis;
    result.facing_fraction = static_cast<double>(facing) / static_cast<double>(nonzero);
    return result;
}

}  // namespace anascan
