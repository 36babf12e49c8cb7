#include "anascan/processing/registration/fine/helical_motion.hpp"

#include <Eigen/Geometry>
#include <cmath>

namespace anascan {
namespace {

// Below this angle (radians) the closed forms lose digits to cancellation and the Taylor
// series (truncated after θ⁴, error < θ⁶/5040 < 1e-15) take over.
constexpr double kSeriesAngleRad = 1e-2;

Eigen::Matrix3d skew(const Eigen::Vector3d& w) {
    Eigen::Matrix3d S;
    S << 0.0, -w.z(), w.y(), w.z(), 0.0, -w.x(), -w.y(), w.x(), 0.0;
    return S;
}

// The three scalar coefficients of the SO(3) exponential and its left Jacobian:
// sin θ / θ, (1 - cos θ) / θ², (θ - sin θ) / θ³.
struct So3Coefficients {
    double sin_over_theta = 1.0;
    double one_minus_cos_over_theta2 = 0.5;
    double theta_minus_sin_over_theta3 = 1.0 / 6.0;
};

So3Coefficients so3_coefficients(double theta) {
    const double t2 = theta * theta;
    if (theta < kSeriesAngleRad) {
        return {1.0 - t2 / 6.0 + t2 * t2 / 120.0, 0.5 - t2 / 24.0 + t2 * t2 / 720.0,
                1.0 / 6.0 - t2 / 120.0 + t2 * t2 / 5040.0};
    }
    const double s = std::sin(theta);
    const double c = std::cos(theta);
    return {s / theta, (1.0 - c) / t2, (theta - s) / (t2 * theta)};
}

// (1 - (θ/2) cot(θ/2)) / θ², the [w]x² coefficient of the inverse left Jacobian.
double inverse_jacobian_coefficient(double theta) {
    const double t2 = theta * theta;
    if (theta < kSeriesAngleRad) return 1.0 / 12.0 + t2 / 720.0 + t2 * t2 / 30240.0;
    const double half = 0.5 * theta;
    return (1.0 - half * std::cos(half) / std::sin(half)) / t2;
}

}  // namespace

Eigen::Matrix3d so3_left_jacobian(const Eigen::Vector3d& angular_rad) {
    const So3Coefficients k = so3_coefficients(angular_rad.norm());
    const Eigen::Matrix3d S = skew(angular_rad);
    return Eigen::Matrix3d::Identity() + k.one_minus_cos_over_theta2 * S +
           k.theta_minus_sin_over_theta3 * S * S;
}

Pose helical_motion(const Twist& twist) {
    const So3Coefficients k = so3_coefficients(twist.angular_rad.norm());
    const Eigen::Matrix3d S = skew(twist.angular_rad);
    const Eigen::Matrix3d S2 = S * S;
    const Eigen::Matrix3d I = Eigen::Matrix3d::Identity();
    Pose T = Pose::Identity();
    T.linear() = I + k.sin_over_theta * S + k.one_minus_cos_over_theta2 * S2;  // Rodrigues.
    const Eigen::Matrix3d V =
        I + k.one_minus_cos_over_theta2 * S + k.theta_minus_sin_over_theta3 * S2;
    T.translation() = V * twist.linear_m;
    return T;
}

Twist helical_twist(const Pose& T) {
    const Eigen::AngleAxisd angle_axis(T.linear());
    Twist twist;
    twist.angular_rad = angle_axis.angle() * angle_axis.axis();
    const double theta = twist.angular_rad.norm();
    const Eigen::Matrix3d S = skew(twist.angular_rad);
    const Eigen::Matrix3d V_inverse =
        Eigen::Matrix3d::Identity() - 0.5 * S + inverse_jacobian_coefficient(theta) * S * S;
    twist.linear_m = V_inverse * T.translation();
    return twist;
}

Twist twist_about_origin(const Twist& twist_about_p, const Eigen::Vector3d& p_m) {
    return {twist_about_p.angular_rad,
            twist_about_p.linear_m - twist_about_p.angular_rad.cross(p_m)};
}

}  // namespace anascan
