#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <random>

#include "anascan/processing/core/pose.hpp"

namespace anascan {
namespace {

constexpr double kDegToRad = std::numbers::pi / 180.0;

Pose rotation_about(const Eigen::Vector3d& axis, double angle_deg) {
    Pose T = Pose::Identity();
    T.linear() = Eigen::AngleAxisd(angle_deg * kDegToRad, axis.normalized()).toRotationMatrix();
    return T;
}

TEST(Pose, RotationAngleOfKnownRotations) {
    EXPECT_EQ(rotation_angle_deg(Pose::Identity()), 0.0);
    EXPECT_NEAR(rotation_angle_deg(rotation_about({0, 0, 1}, 90.0)), 90.0, 1e-10);
    EXPECT_NEAR(rotation_angle_deg(rotation_about({1, 2, 3}, 37.5)), 37.5, 1e-10);
    EXPECT_NEAR(rotation_angle_deg(rotation_about({1, 0, 0}, -30.0)), 30.0, 1e-10);
    EXPECT_NEAR(rotation_angle_deg(rotation_about({0, 1, 0}, 270.0)), 90.0, 1e-10);
}

TEST(Pose, RotationAngleKeepsTinyAngles) {
    for (double angle : {1e-6, 3e-5, 1e-3}) {
        const double got = rotation_angle_deg(rotation_about({0.3, -1, 0.2}, angle));
        EXPECT_NEAR(got, angle, angle * 1e-6) << angle;
    }
}

TEST(Pose, RotationAngleAtHalfTurn) {
    EXPECT_NEAR(rotation_angle_deg(rotation_about({0, 0, 1}, 180.0)), 180.0, 1e-9);
    EXPECT_NEAR(rotation_angle_deg(rotation_about({1, 1, 0}, 180.0)), 180.0, 1e-9);
    const double just_below = rotation_angle_deg(rotation_about({0, 1, 0}, 179.999));
    EXPECT_NEAR(just_below, 179.999, 1e-7);
    EXPECT_LE(rotation_angle_deg(rotation_about({1, 0, 1}, 180.0)), 180.0);
}

TEST(Pose, MakePoseNormalisesTheQuaternion) {
    const Eigen::Quaterniond q(2.0, 0.0, 0.0, 2.0);  // 90 deg about z, not unit length.
    const Pose T = make_pose(q, {1.0, 2.0, 3.0});
    EXPECT_NEAR(rotation_angle_deg(T), 90.0, 1e-10);
    EXPECT_TRUE((T * Eigen::Vector3d(1, 0, 0)).isApprox(Eigen::Vector3d(1, 3, 3), 1e-12));
    EXPECT_NEAR(T.linear().determinant(), 1.0, 1e-12);
}

TEST(Pose, PoseDifference) {
    const Pose a = make_pose(Eigen::Quaterniond(Eigen::AngleAxisd(0.3, Eigen::Vector3d::UnitX())),
                             {1.0, 0.0, 0.0});
    Pose b = a;
    b.translation() += Eigen::Vector3d(0.0, 0.003, 0.004);
    b.linear() = b.linear() * rotation_about({0, 0, 1}, 2.0).linear();
    const PoseDifference d = pose_difference(a, b);
    EXPECT_NEAR(d.rotation_deg, 2.0, 1e-9);
    EXPECT_NEAR(d.translation_m, 0.005, 1e-12);
    const PoseDifference same = pose_difference(a, a);
    EXPECT_NEAR(same.rotation_deg, 0.0, 1e-9);
    EXPECT_EQ(same.translation_m, 0.0);
}

TEST(Pose, TransformedKeepsPrecisionForLargeOrigins) {
    std::mt19937 rng(21);
    std::uniform_real_distribution<float> local(-2.0f, 2.0f);
    PointCloud cloud;
    cloud.origin_m = {5.0e5, 5.0e5, 250.0};
    for (int i = 0; i < 1000; ++i) {
        cloud.positions.emplace_back(local(rng), local(rng), local(rng));
        cloud.normals.push_back(cloud.positions.back().normalized());
    }
    const Pose T_to_from =
        make_pose(Eigen::Quaterniond(Eigen::AngleAxisd(0.7, Eigen::Vector3d(1, 2, 3).normalized())),
                  {-4.99e5, 1.2e5, 33.3});
    const PointCloud out = transformed(cloud, T_to_from);
    ASSERT_EQ(out.size(), cloud.size());
    for (std::size_t i = 0; i < cloud.size(); ++i) {
        const Eigen::Vector3d expected = T_to_from * cloud.world_position(i);
        EXPECT_LT((out.world_position(i) - expected).norm(), 1e-6) << "point " << i;
        const Eigen::Vector3d normal = T_to_from.linear() * cloud.normals[i].cast<double>();
        EXPECT_LT((out.normals[i].cast<double>() - normal).norm(), 1e-6) << "normal " << i;
    }
}

TEST(Pose, TransformedByInverseRestoresTheCloud) {
    PointCloud cloud;
    cloud.origin_m = {5.0e5, -3.0e5, 10.0};
    cloud.positions = {{0.1f, 0.2f, 0.3f}, {-1.0f, 0.5f, 2.0f}};
    const Pose T = make_pose(Eigen::Quaterniond(0.9, 0.1, -0.3, 0.2), {12.0, -7.0, 1e5});
    const PointCloud back = transformed(transformed(cloud, T), T.inverse());
    for (std::size_t i = 0; i < cloud.size(); ++i) {
        EXPECT_LT((back.world_position(i) - cloud.world_position(i)).norm(), 1e-6);
    }
}

TEST(Pose, OrthonormalizedFixesAPerturbedRotation) {
    const Pose T = make_pose(Eigen::Quaterniond(0.8, 0.2, 0.4, -0.1), {1.0, 2.0, 3.0});
    Pose perturbed = T;
    std::mt19937 rng(5);
    std::normal_distribution<double> noise(0.0, 1e-4);
    for (int r = 0; r < 3; ++r) {
        for (int c = 0; c < 3; ++c) perturbed.linear()(r, c) += noise(rng);
    }
    ASSERT_GT(
        (perturbed.linear().transpose() * perturbed.linear() - Eigen::Matrix3d::Identity()).norm(),
        1e-5);
    const Pose fixed = orthonormalized(perturbed);
    const Eigen::Matrix3d R = fixed.linear();
    EXPECT_LT((R.transpose() * R - Eigen::Matrix3d::Identity()).norm(), 1e-12);
    EXPECT_NEAR(R.determinant(), 1.0, 1e-12);
    EXPECT_LT(pose_difference(T, fixed).rotation_deg, 0.05);
    EXPECT_EQ(fixed.translation(), T.translation());
}

}  // namespace
}  // namespace anascan
