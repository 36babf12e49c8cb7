// The helical motion of a linear velocity field against closed-form screw motions built
// from Eigen::AngleAxis, its first-order agreement with x + v(x), and its inverse.
#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <array>
#include <cmath>

#include "anascan/processing/registration/fine/helical_motion.hpp"

namespace anascan {
namespace {

// Angles on both sides of the series switch (1e-2 rad), tiny, moderate and large.
constexpr std::array<double, 8> kAnglesRad{0.0, 1e-9, 1e-4, 0.0099999, 0.0100001, 0.3, 1.7, 3.1};

Eigen::Vector3d unit(double x, double y, double z) { return Eigen::Vector3d(x, y, z).normalized(); }

// Screw motion: rotate by `angle` about the axis through `p` with direction `axis`, then
// slide `slide_m` along the axis (Eigen's own constructions, the oracle).
Pose screw(const Eigen::Vector3d& axis, double angle, const Eigen::Vector3d& p, double slide_m) {
    Pose T = Pose::Identity();
    T = Eigen::Translation3d(slide_m * axis) * Eigen::Translation3d(p) *
        Eigen::AngleAxisd(angle, axis) * Eigen::Translation3d(-p);
    return T;
}

void expect_pose_near(const Pose& a, const Pose& b, double tolerance) {
    EXPECT_LT((a.matrix() - b.matrix()).cwiseAbs().maxCoeff(), tolerance) << "a =\n"
                                                                          << a.matrix() << "\nb =\n"
                                                                          << b.matrix();
}

TEST(HelicalMotion, ZeroTwistIsIdentity) {
    EXPECT_EQ(helical_motion(Twist{}).matrix(), Pose::Identity().matrix());
}

TEST(HelicalMotion, PureTranslationMovesByLinearPart) {
    const Twist twist{Eigen::Vector3d::Zero(), Eigen::Vector3d(0.3, -0.2, 1.5)};
    const Pose T = helical_motion(twist);
    EXPECT_TRUE(T.linear().isIdentity(0.0));
    EXPECT_EQ(T.translation(), twist.linear_m);
}

// A rotation about the axis through p has velocity v(x) = c × (x - p), so c̄ = -c × p = p × c.
TEST(HelicalMotion, RotationAboutAxisThroughPointKeepsEveryAxisPointFixed) {
    const Eigen::Vector3d axis = unit(1.0, 2.0, -0.5);
    const Eigen::Vector3d p(0.4, -1.2, 2.0);
    for (double angle : kAnglesRad) {
        const Eigen::Vector3d c = angle * axis;
        const Pose T = helical_motion(Twist{c, p.cross(c)});
        EXPECT_LT((T * p - p).norm(), 1e-14) << angle;
        EXPECT_LT((T * (p + 3.0 * axis) - (p + 3.0 * axis)).norm(), 1e-14) << angle;
        expect_pose_near(T, screw(axis, angle, p, 0.0), 1e-14);
    }
}

// General twist: rotation about the axis through p plus a slide of pitch × angle along it;
// c̄ = p × c + pitch c.
TEST(HelicalMotion, MatchesScrewBuiltFromAngleAxis) {
    const Eigen::Vector3d axis = unit(-0.3, 0.8, 0.52);
    const Eigen::Vector3d p(1.0, 0.5, -0.25);  // Any point on the axis.
    const double pitch_m = 0.07;
    for (double angle : kAnglesRad) {
        const Eigen::Vector3d c = angle * axis;
        const Pose T = helical_motion(Twist{c, p.cross(c) + pitch_m * c});
        expect_pose_near(T, screw(axis, angle, p, pitch_m * angle), 1e-14);
    }
}

// x' = x + v(x) + O(|twist|²): the affine map is only the first-order approximation.
TEST(HelicalMotion, SmallTwistMatchesAffineVelocityToFirstOrder) {
    const Twist unit_twist{Eigen::Vector3d(0.3, -0.7, 0.2), Eigen::Vector3d(0.05, 0.1, -0.2)};
    const Eigen::Vector3d x(0.8, -0.4, 1.1);
    for (double eps : {1e-2, 1e-3, 1e-4}) {
        const Twist twist{eps * unit_twist.angular_rad, eps * unit_twist.linear_m};
        const Eigen::Vector3d moved = helical_motion(twist) * x;
        const Eigen::Vector3d affine = x + twist.velocity(x);
        EXPECT_LT((moved - affine).norm(), 2.0 * eps * eps) << eps;
        EXPECT_GT((moved - affine).norm(), 0.01 * eps * eps) << "second-order term missing";
    }
}

TEST(HelicalMotion, IsRigidAndMovesOffAxisPointsOnCircles) {
    const Eigen::Vector3d axis = unit(0.0, 0.0, 1.0);
    const Eigen::Vector3d c = 1.7 * axis;
    const Pose T = helical_motion(Twist{c, Eigen::Vector3d::Zero()});
    EXPECT_LT((T.linear().transpose() * T.linear() - Eigen::Matrix3d::Identity()).norm(), 1e-15);
    EXPECT_NEAR(T.linear().determinant(), 1.0, 1e-15);
    const Eigen::Vector3d x(2.0, 0.0, 0.5);
    EXPECT_NEAR((T * x).head<2>().norm(), 2.0, 1e-15);  // Not x + v(x), which leaves the circle.
    EXPECT_NEAR((T * x).z(), 0.5, 1e-15);
}

// Motions of one twist commute: exp(s ξ) exp(t ξ) = exp((s + t) ξ).
TEST(HelicalMotion, OneParameterGroupComposes) {
    const Twist twist{Eigen::Vector3d(0.2, -0.4, 0.9), Eigen::Vector3d(0.3, 0.1, -0.6)};
    const auto scaled = [&](double s) { return Twist{s * twist.angular_rad, s * twist.linear_m}; };
    expect_pose_near(helical_motion(scaled(0.3)) * helical_motion(scaled(0.7)),
                     helical_motion(twist), 1e-14);
    expect_pose_near(helical_motion(scaled(-1.0)), helical_motion(twist).inverse(), 1e-14);
}

TEST(HelicalMotion, LeftJacobianMatchesIntegralOfRotations) {
    for (double angle : kAnglesRad) {
        const Eigen::Vector3d c = angle * unit(0.6, -0.2, 0.77);
        Eigen::Matrix3d integral = Eigen::Matrix3d::Zero();
        constexpr int kSteps = 2000;  // Simpson's rule over s in [0, 1].
        for (int k = 0; k <= kSteps; ++k) {
            const double s = static_cast<double>(k) / kSteps;
            const double w = (k == 0 || k == kSteps) ? 1.0 : (k % 2 == 1 ? 4.0 : 2.0);
            const Eigen::Vector3d cs = s * c;
            const Eigen::Matrix3d R = cs.norm() > 0.0
                                          ? Eigen::AngleAxisd(cs.norm(), cs.normalized()).matrix()
                                          : Eigen::Matrix3d::Identity();
            integral += w * R / (3.0 * kSteps);
        }
        EXPECT_LT((so3_left_jacobian(c) - integral).cwiseAbs().maxCoeff(), 1e-12) << angle;
    }
}

TEST(HelicalMotion, TwistOfMotionRoundTrips) {
    for (double angle : kAnglesRad) {
        const Twist twist{angle * unit(-0.1, 0.9, 0.4), Eigen::Vector3d(0.02, -0.3, 0.11)};
        const Twist back = helical_twist(helical_motion(twist));
        EXPECT_LT((back.angular_rad - twist.angular_rad).norm(), 1e-13) << angle;
        EXPECT_LT((back.linear_m - twist.linear_m).norm(), 1e-13) << angle;
    }
}

TEST(HelicalMotion, TwistAboutPointDescribesTheSameField) {
    const Twist about_p{Eigen::Vector3d(0.1, 0.2, -0.3), Eigen::Vector3d(0.5, -0.1, 0.2)};
    const Eigen::Vector3d p(2.0, -1.0, 0.5);
    const Twist about_origin = twist_about_origin(about_p, p);
    for (const Eigen::Vector3d& x : {Eigen::Vector3d(0, 0, 0), Eigen::Vector3d(1, 2, 3), p}) {
        EXPECT_LT((about_origin.velocity(x) - about_p.velocity(x - p)).norm(), 1e-15);
    }
}

}  // namespace
}  // namespace anascan
