#include <gtest/gtest.h>

#include "anascan/processing/evaluation/pose_evaluation.hpp"

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

TEST(PoseEvaluation, TheBestFitFrameDoesNotChargeTheReferenceScansErrorToTheOthers) {
    // Four scans 1 m apart, measured at their origins; the reference scan alone is off by
    // 1 mm. In its frame every other scan looks 1 mm off; in the best-fit frame the error
    // is shared: the reference about 0.75 mm off, the others about 0.25 mm.
    std::vector<NamedPose> truth;
    for (int i = 0; i < 4; ++i)
        truth.push_back({std::string(1, static_cast<char>('a' + i)),
                         pose(20.0 * i, {0, 0, 1}, {1.0 * i, 0.5 * (i % 2), 0})});
    std::vector<NamedPose> estimated = truth;
    estimated[0].T_world_scan = Pose(Eigen::Translation3d(0.001, 0, 0)) * truth[0].T_world_scan;
    const auto eval = evaluate_poses(estimated, truth);
    ASSERT_TRUE(eval.has_value());
    EXPECT_NEAR(eval->max_translation_m, 0.001, 1e-9);
    EXPECT_NEAR(eval->max_translation_best_fit_m, 0.00075, 5e-5);
    EXPECT_LT(eval->max_rotation_best_fit_deg, 0.05);
    // Fewer than three scans: the reference frame's figures.
    const auto two = evaluate_poses({estimated[0], estimated[1]}, {truth[0], truth[1]});
    ASSERT_TRUE(two.has_value());
    EXPECT_EQ(two->max_translation_best_fit_m, two->max_translation_m);
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
