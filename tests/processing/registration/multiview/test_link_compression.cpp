// compress_link: a thinned link keeps the optimum and the stiffness of all its
// correspondences (docs/multiview-refinement.md, "Compact links").
#include <gtest/gtest.h>

#include <cmath>
#include <numeric>
#include <random>

#include "anascan/processing/registration/multiview/link_compression.hpp"
#include "anascan/processing/registration/multiview/multiview_refinement.hpp"

namespace anascan {
namespace {

/// Correspondences between two views of a bumpy patch (identity pose, target frame = source
/// frame), with 0.1 mm of noise along the normals: the noise makes the optimum of any subset
/// differ from the optimum of all of them.
std::vector<FineCorrespondence> noisy_link(std::size_t count) {
    std::mt19937 rng(7);
    std::uniform_real_distribution<double> u(-0.1, 0.1);
    std::normal_distribution<double> noise(0.0, 1e-4);
    std::vector<FineCorrespondence> out;
    for (std::size_t i = 0; i < count; ++i) {
        const double x = u(rng), y = u(rng);
        const double z = 0.01 * std::sin(40.0 * x) * std::cos(30.0 * y);
        const Eigen::Vector3d n =
            Eigen::Vector3d(-0.4 * std::cos(40.0 * x) * std::cos(30.0 * y),
                            0.3 * std::sin(40.0 * x) * std::sin(30.0 * y), 1.0)
                .normalized();
        FineCorrespondence c;
        c.source_point_m = Eigen::Vector3d(x, y, z + 1.0);
        c.target_point_m = c.source_point_m + noise(rng) * n;
        c.target_normal = n.cast<float>();
        c.weight = 0.5 + 0.5 * std::abs(u(rng)) * 10.0;
        out.push_back(c);
    }
    return out;
}

/// The free scan's pose that the link alone pulls it to (scan 0 fixed at the identity).
Pose optimum(const std::vector<FineCorrespondence>& correspondences) {
    const std::vector<Pose> poses = {Pose::Identity(), Pose::Identity()};
    const std::vector<MultiviewLink> links = {
        {.target_index = 0, .source_index = 1, .correspondences = correspondences}};
    const MultiviewRefinementResult r =
        refine_multiview(poses, links, {.fixed_scan_index = 0, .max_link_rms_m = 1.0});
    EXPECT_TRUE(r.converged) << to_string(r.status);
    return r.T_world_scan[1];
}

double displacement_m(const Pose& a, const Pose& b) {
    const Eigen::Vector3d centre(0.0, 0.0, 1.0);  // The patch's centre.
    return (a * centre - b * centre).norm() +
           0.1 * rotation_angle_deg(a.inverse() * b) * M_PI / 180.0;  // Rotation at 0.1 m.
}

double weight_sum(const std::vector<FineCorrespondence>& cs) {
    return std::accumulate(cs.begin(), cs.end(), 0.0,
                           [](double s, const FineCorrespondence& c) { return s + c.weight; });
}

TEST(LinkCompression, KeepsTheOptimumOfAllCorrespondences) {
    const std::vector<FineCorrespondence> all = noisy_link(20000);
    const Pose T_all = optimum(all);
    const std::vector<FineCorrespondence> compact = compress_link(all, T_all, 500);
    ASSERT_LE(compact.size(), 500u);
    ASSERT_GE(compact.size(), 400u);
    EXPECT_NEAR(weight_sum(compact), weight_sum(all), 1e-6 * weight_sum(all));
    const double kept_error = displacement_m(optimum(compact), T_all);
    // The same subset without the shift: its own optimum, off by its sampling noise.
    std::vector<FineCorrespondence> plain;
    for (std::size_t i = 0; i < all.size(); i += all.size() / compact.size())
        plain.push_back(all[i]);
    const double plain_error = displacement_m(optimum(plain), T_all);
    EXPECT_LT(kept_error, 1e-8);
    EXPECT_GT(plain_error, 100.0 * kept_error);
}

TEST(LinkCompression, LeavesFewCorrespondencesAsTheyAre) {
    const std::vector<FineCorrespondence> all = noisy_link(300);
    const std::vector<FineCorrespondence> same = compress_link(all, Pose::Identity(), 500);
    ASSERT_EQ(same.size(), all.size());
    for (std::size_t i = 0; i < all.size(); ++i) {
        EXPECT_EQ(same[i].target_point_m, all[i].target_point_m);
        EXPECT_EQ(same[i].weight, all[i].weight);
    }
    EXPECT_EQ(compress_link(all, Pose::Identity(), 0).size(), all.size());
    EXPECT_TRUE(compress_link({}, Pose::Identity(), 10).empty());
}

}  // namespace
}  // namespace anascan
