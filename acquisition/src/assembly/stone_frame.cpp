#include "anascan/acquisition/assembly/stone_frame.hpp"

#include <Eigen/Eigenvalues>
#include <vector>

#include "anascan/processing/cleaning/plane_removal.hpp"

namespace anascan::acquisition {
namespace {

struct Moments {
    Eigen::Vector3d mean = Eigen::Vector3d::Zero();
    Eigen::Matrix3d covariance = Eigen::Matrix3d::Zero();
};

/// Mean and covariance of the model's points (local frame), those with keep[i] only.
Moments moments(const PointCloud& model, const std::vector<bool>& keep) {
    Moments m;
    std::size_t n = 0;
    for (std::size_t i = 0; i < model.size(); ++i)
        if (keep[i] && model.positions[i].allFinite())
            m.mean += model.positions[i].cast<double>(), ++n;
    if (n == 0) return m;
    m.mean /= static_cast<double>(n);
    for (std::size_t i = 0; i < model.size(); ++i) {
        if (!keep[i] || !model.positions[i].allFinite()) continue;
        const Eigen::Vector3d d = model.positions[i].cast<double>() - m.mean;
        m.covariance += d * d.transpose();
    }
    m.covariance /= static_cast<double>(n);
    return m;
}

/// Rotation whose rows are the stone axes x, y, z (z = up, x = the longest extent
/// perpendicular to up), right-handed.
Eigen::Matrix3d axes(const Eigen::Vector3d& up, const Eigen::Matrix3d& covariance) {
    const Eigen::Matrix3d across = Eigen::Matrix3d::Identity() - up * up.transpose();
    const Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> solver(across * covariance * across);
    Eigen::Vector3d x = solver.eigenvectors().col(2).normalized();  // Largest eigenvalue.
    if (x.x() + x.y() + x.z() < 0.0) x = -x;                        // A reproducible sign.
    Eigen::Matrix3d R;
    R.row(0) = x.transpose();
    R.row(1) = up.cross(x).transpose();
    R.row(2) = up.transpose();
    return R;
}

}  // namespace

StoneFrame stone_frame(const PointCloud& model, const StoneFrameConfig& config) {
    StoneFrame frame;
    std::vector<bool> stone(model.size(), true);
    const PlaneFitResult fit =
        find_dominant_plane(model, {.distance_threshold_m = config.ground_band_m,
                                    .min_inlier_fraction = config.min_ground_fraction});
    Eigen::Vector3d up;
    frame.ground_found = fit.status == PlaneFitStatus::kOk;
    if (frame.ground_found) {
        for (std::size_t i = 0; i < model.size(); ++i)
            stone[i] = fit.plane.signed_distance_m(model.positions[i]) > config.ground_band_m;
        up = fit.plane.normal;
    }
    const Moments m = moments(model, stone);
    if (!frame.ground_found) {
        const Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> solver(m.covariance);
        up = solver.eigenvectors().col(0).normalized();  // Smallest extent.
    }
    const Eigen::Matrix3d R = axes(up, m.covariance);
    Eigen::Vector3d origin = m.mean;  // Local frame of the model.
    if (frame.ground_found) origin -= up * fit.plane.signed_distance_m(m.mean.cast<float>());
    Pose T_stone_local = Pose::Identity();
    T_stone_local.linear() = R;
    T_stone_local.translation() = -R * origin;
    Pose T_local_model(Eigen::Translation3d(-model.origin_m));
    frame.T_stone_model = T_stone_local * T_local_model;
    frame.description = frame.ground_found
                            ? "stone frame: +z up from the ground plane, origin on the ground "
                              "under the stone's centroid, +x along its longest side"
                            : "stone frame: no ground plane found; principal axes at the "
                              "stone's centroid (+z its thinnest direction)";
    return frame;
}

}  // namespace anascan::acquisition
