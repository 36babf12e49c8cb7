// The stone's frame the hints speak in: up from the ground the stone rests on now, +x along
// its longest horizontal extent (the long sides are ±y), origin on the ground under the
// surface's centre. Without a ground (no view showed one), up is the caller's hint, else the
// surface's thinnest direction turned toward -y of the model frame: the model frame is the
// first scan's camera frame, whose image y points down when the scanner is held upright.

#include <Eigen/Eigenvalues>
#include <limits>

#include "planning/steps.hpp"

namespace anascan {
namespace {

struct SurfaceMoments {
    Eigen::Vector3d mean = Eigen::Vector3d::Zero();
    Eigen::Matrix3d covariance = Eigen::Matrix3d::Zero();
};

SurfaceMoments moments(const PointCloud& vertices) {
    SurfaceMoments m;
    if (vertices.empty()) return m;
    for (std::size_t i = 0; i < vertices.size(); ++i) m.mean += vertices.world_position(i);
    m.mean /= static_cast<double>(vertices.size());
    for (std::size_t i = 0; i < vertices.size(); ++i) {
        const Eigen::Vector3d d = vertices.world_position(i) - m.mean;
        m.covariance += d * d.transpose();
    }
    m.covariance /= static_cast<double>(vertices.size());
    return m;
}

Eigen::Vector3d up_without_ground(const Eigen::Matrix3d& covariance) {
    const Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> solver(covariance);
    Eigen::Vector3d up = solver.eigenvectors().col(0).normalized();
    return up.y() > 0.0 ? -up : up;
}

}  // namespace

PlanningFrame planning_frame(const CoverageReport& coverage,
                             const std::optional<Eigen::Vector3d>& up_hint_world) {
    PlanningFrame frame;
    const PointCloud& vertices = coverage.surface.vertices;
    const SurfaceMoments m = moments(vertices);
    frame.ground_known = coverage.ground_world.has_value();
    Eigen::Vector3d up = up_without_ground(m.covariance);
    if (frame.ground_known)
        up = coverage.ground_world->normal.normalized();
    else if (up_hint_world && up_hint_world->norm() > 0.0)
        up = up_hint_world->normalized();
    const Eigen::Matrix3d across = Eigen::Matrix3d::Identity() - up * up.transpose();
    const Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> solver(across * m.covariance * across);
    Eigen::Vector3d x = solver.eigenvectors().col(2).normalized();
    if (x.sum() < 0.0) x = -x;  // A reproducible sign.
    frame.R_stone_world.row(0) = x.transpose();
    frame.R_stone_world.row(1) = up.cross(x).transpose();
    frame.R_stone_world.row(2) = up.transpose();
    double base = 0.0;
    if (frame.ground_known) {
        base = -coverage.ground_world->offset_m;  // up · p on the ground.
    } else {
        base = std::numeric_limits<double>::infinity();
        for (std::size_t i = 0; i < vertices.size(); ++i)
            base = std::min(base, up.dot(vertices.world_position(i)));
        if (vertices.empty()) base = 0.0;
    }
    frame.origin_world_m = m.mean - up * (up.dot(m.mean) - base);
    Eigen::Vector3d lo = Eigen::Vector3d::Constant(std::numeric_limits<double>::infinity());
    Eigen::Vector3d hi = -lo;
    for (std::size_t i = 0; i < vertices.size(); ++i) {
        const Eigen::Vector3d p = frame.to_stone(vertices.world_position(i));
        lo = lo.cwiseMin(p), hi = hi.cwiseMax(p);
    }
    if (!vertices.empty()) frame.extent_m = hi - lo;
    return frame;
}

}  // namespace anascan
