#include "anascan/processing/core/pose.hpp"

#include <Eigen/SVD>
#include <cmath>
#include <numbers>

namespace anascan {

double rotation_angle_deg(const Pose& T_a_b) {
    // acos of the trace loses precision near 0; the quaternion form keeps tiny angles exact.
    const Eigen::Quaterniond q(T_a_b.linear());
    const double angle_rad = 2.0 * std::atan2(q.vec().norm(), std::abs(q.w()));
    return angle_rad * 180.0 / std::numbers::pi;
}

PoseDifference pose_difference(const Pose& a, const Pose& b) {
    const Pose delta = a.inverse() * b;
    return {rotation_angle_deg(delta), (b.translation() - a.translation()).norm()};
}

Pose make_pose(const Eigen::Quaterniond& q, const Eigen::Vector3d& t_m) {
    Pose T = Pose::Identity();
    T.linear() = q.normalized().toRotationMatrix();
    T.translation() = t_m;
    return T;
}

PointCloud transformed(const PointCloud& cloud_from, const Pose& T_to_from) {
    PointCloud out = cloud_from;
    out.origin_m = T_to_from * cloud_from.origin_m;
    const Eigen::Matrix3f R = T_to_from.linear().cast<float>();
    for (Eigen::Vector3f& p : out.positions) p = R * p;
    for (Eigen::Vector3f& n : out.normals) n = R * n;
    return out;
}

Pose orthonormalized(const Pose& T) {
    const Eigen::JacobiSVD<Eigen::Matrix3d> svd(T.linear(),
                                                Eigen::ComputeFullU | Eigen::ComputeFullV);
    Eigen::Matrix3d R = svd.matrixU() * svd.matrixV().transpose();
    if (R.determinant() < 0) {
        Eigen::Matrix3d U = svd.matrixU();
        U.col(2) *= -1.0;
        R = U * svd.matrixV().transpose();
    }
    Pose out = Pose::Identity();
    out.linear() = R;
    out.translation() = T.translation();
    return out;
}

Pose look_at(const Eigen::Vector3d& eye, const Eigen::Vector3d& target, const Eigen::Vector3d& up) {
    const Eigen::Vector3d z = (target - eye).normalized();
    Eigen::Vector3d x = z.cross(up);
    if (x.norm() < 1e-9) x = z.cross(Eigen::Vector3d::UnitX());  // Looking along up.
    x.normalize();
    Pose T = Pose::Identity();
    T.linear().col(0) = x;
    T.linear().col(1) = z.cross(x);
    T.linear().col(2) = z;
    T.translation() = eye;
    return T;
}

}  // namespace anascan
