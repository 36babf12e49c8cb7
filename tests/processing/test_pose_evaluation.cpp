#include <gtest/gtest.h>

#include "anascan/processing/pose_evaluation.hpp"

namespace anascan {
namespace {

Pose pose(double angle_deg, const Eigen::Vector3d& axis, const Eigen::Vector3d& t) {
    return make_pose(
        Eigen::Quaterniond(Eigen::AngleAxisd(angle_deg * M_PI / 180, axis.normalized())), t);
}

TEST(PoseEvaluation, ACommonRigidMotionIsNotAnError) {
    const std::vector<NamedPose> truth = {{"a", pose(0, {0, 0, 1}, {0, 0, 0})},
                                          {"b", pose(30, {0, 1, 0}, {0.1, 0, 0})},
                                          {"c", pose(-50, {1, 1, 0}, {0, 0.2, 0.05})}};
    const Pose motion = pose(77, {1, 2, 3}, {5, -3, 2});
    std::vector<NamedPose> estimated;
    for (const NamedPose& t : truth) estimated.push_back({t.name, motion * t.T_world_scan});
    const auto eval = evaluate_poses(estimated, truth);
    ASSERT_TRUE(eval.has_value());
    EXPECT_EQ(eval->reference, "a");
    EXPECT_EQ(eval->placed, 3u);
    EXPECT_LT(eval->max_rotation_deg, 1e-9);
    EXPECT_LT(eval->max_translation_m, 1e-12);
}

TEST(PoseEvaluation, ReportsTheErrorOfOneScan) {
    const std::vector<NamedPose> truth = {{"a", Pose::Identity()},
                                          {"b", pose(10, {0, 0, 1}, {0.1, 0, 0})}};
    std::vector<NamedPose> estimated = truth;
    estimated[1].T_world_scan = estimated[1].T_world_scan * pose(0.5, {1, 0, 0}, {0.002, 0, 0});
    const auto eval = evaluate_poses(estimated, truth);
    ASSERT_TRUE(eval.has_value());
    EXPECT_NEAR(eval->scans[1].rotation_deg, 0.5, 1e-9);
    // The local offset of 2 mm, rotated by the scan's 10 degrees, is still 2 mm long.
    EXPECT_NEAR(eval->scans[1].translation_m, 0.002, 1e-12);
}

TEST(PoseEvaluation, MissingAndUnknownScansAreListed) {
    const std::vector<NamedPose> truth = {{"a", Pose::Identity()}, {"b", Pose::Identity()}};
    const std::vector<NamedPose> estimated = {{"a", Pose::Identity()}, {"z", Pose::Identity()}};
    const auto eval = evaluate_poses(estimated, truth);
    ASSERT_TRUE(eval.has_value());
    EXPECT_FALSE(eval->scans[1].placed);
    EXPECT_EQ(eval->placed, 1u);
    ASSERT_EQ(eval->unknown.size(), 1u);
    EXPECT_EQ(eval->unknown[0], "z");
}

TEST(PoseEvaluation, NoCommonScanIsNoEvaluation) {
    EXPECT_FALSE(evaluate_poses({{"x", Pose::Identity()}}, {{"y", Pose::Identity()}}).has_value());
}

}  // namespace
}  // namespace anascan
