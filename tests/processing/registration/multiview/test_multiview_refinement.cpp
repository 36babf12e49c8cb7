// Multi-view refinement (paper eq. 4) on synthetic views of a lumpy closed surface with
// known true poses: exact correspondences from the truth, perturbed starting poses (1°,
// 2 mm), a biased link, an unlinked scan, a planar (sliding) pair.
#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <cmath>
#include <cstdio>
#include <numbers>
#include <random>
#include <vector>

#include "anascan/processing/core/pose.hpp"
#include "anascan/processing/registration/multiview/multiview_refinement.hpp"

namespace anascan {
namespace {

constexpr double kDeg = std::numbers::pi / 180.0;

// A non-symmetric lumpy closed surface about the origin (radius ~0.1 m), by direction.
Eigen::Vector3d surface_point(double theta, double phi) {
    const double r = 0.1 * (1.0 + 0.12 * std::sin(3.0 * theta) * std::cos(2.0 * phi) +
                            0.07 * std::sin(5.0 * phi + 1.0) * std::sin(2.0 * theta) +
                            0.05 * std::cos(4.0 * theta + 0.5));
    return r * Eigen::Vector3d(std::sin(theta) * std::cos(phi), std::sin(theta) * std::sin(phi),
                               std::cos(theta));
}

Eigen::Vector3d surface_normal(double theta, double phi) {
    constexpr double h = 1e-6;
    const Eigen::Vector3d dt = surface_point(theta + h, phi) - surface_point(theta - h, phi);
    const Eigen::Vector3d dp = surface_point(theta, phi + h) - surface_point(theta, phi - h);
    Eigen::Vector3d n = dt.cross(dp).normalized();
    return n.dot(surface_point(theta, phi)) < 0.0 ? -n : n;  // Outward.
}

struct SurfaceSample {
    Eigen::Vector3d point;   // World.
    Eigen::Vector3d normal;  // World, outward.
};

std::vector<SurfaceSample> surface_samples() {
    std::vector<SurfaceSample> samples;
    for (int i = 1; i < 40; ++i) {
        for (int j = 0; j < 80; ++j) {
            const double theta = std::numbers::pi * i / 40.0;
            const double phi = 2.0 * std::numbers::pi * j / 80.0;
            samples.push_back({surface_point(theta, phi), surface_normal(theta, phi)});
        }
    }
    return samples;
}

struct Scene {
    std::vector<Pose> T_world_scan_truth;
    std::vector<Eigen::Vector3d> view_directions;  // World.
    std::vector<SurfaceSample> samples;
};

Pose random_pose(std::mt19937& rng, double max_angle_rad, double max_shift_m) {
    std::uniform_real_distribution<double> u(-1.0, 1.0);
    const Eigen::Vector3d axis(u(rng), u(rng), u(rng));
    Pose T = Pose::Identity();
    T.linear() = Eigen::AngleAxisd(max_angle_rad * u(rng), axis.normalized()).toRotationMatrix();
    T.translation() = max_shift_m * Eigen::Vector3d(u(rng), u(rng), u(rng));
    return T;
}

Scene make_scene() {
    Scene scene;
    scene.samples = surface_samples();
    scene.view_directions = {{1, 0, 0}, {0, 1, 0},  {-1, 0, 0}, {0, -1, 0},
                             {0, 0, 1}, {0, 0, -1}, {1, 1, 1},  {-1, 1, -1}};
    std::mt19937 rng(7);
    for (Eigen::Vector3d& v : scene.view_directions) {
        v.normalize();
        scene.T_world_scan_truth.push_back(random_pose(rng, std::numbers::pi, 1.0));
    }
    return scene;
}

bool visible(const Scene& scene, std::size_t scan, const SurfaceSample& s) {
    return s.normal.dot(scene.view_directions[scan]) > 0.2;
}

// Correspondences of link (target j, source k) consistent with the relative pose
// T_world_k_used (the truth for a good link): the same surface points seen by both scans.
MultiviewLink make_link(const Scene& scene, std::size_t j, std::size_t k,
                        const Pose& T_world_k_used) {
    MultiviewLink link{.target_index = j, .source_index = k, .correspondences = {}};
    const Pose& T_world_j = scene.T_world_scan_truth[j];
    for (std::size_t i = 0; i < scene.samples.size(); i += 3) {
        const SurfaceSample& s = scene.samples[i];
        if (!visible(scene, j, s) || !visible(scene, k, s)) continue;
        FineCorrespondence c;
        c.source_point_m = scene.T_world_scan_truth[k].inverse() * s.point;
        c.target_point_m = T_world_j.inverse() * (T_world_k_used * c.source_point_m);
        c.target_normal = (T_world_j.linear().transpose() * T_world_k_used.linear() *
                           scene.T_world_scan_truth[k].linear().transpose() * s.normal)
                              .cast<float>();
        link.correspondences.push_back(c);
    }
    return link;
}

std::vector<MultiviewLink> make_links(const Scene& scene) {
    std::vector<MultiviewLink> links;
    for (std::size_t j = 0; j < scene.T_world_scan_truth.size(); ++j) {
        for (std::size_t k = j + 1; k < scene.T_world_scan_truth.size(); ++k) {
            MultiviewLink link = make_link(scene, j, k, scene.T_world_scan_truth[k]);
            if (link.correspondences.size() >= 50) links.push_back(std::move(link));
        }
    }
    return links;
}

// Every pose moved by 1° about a random axis through the scan's world centroid (the
// surface centre, the world origin here) and by 2 mm in a random direction.
std::vector<Pose> perturbed(const std::vector<Pose>& truth, unsigned seed) {
    std::mt19937 rng(seed);
    std::normal_distribution<double> g(0.0, 1.0);
    std::vector<Pose> poses;
    for (const Pose& T : truth) {
        const Eigen::Vector3d axis(g(rng), g(rng), g(rng));
        const Eigen::Vector3d dir(g(rng), g(rng), g(rng));
        Pose delta = Pose::Identity();
        delta.linear() = Eigen::AngleAxisd(1.0 * kDeg, axis.normalized()).toRotationMatrix();
        delta.translation() = 0.002 * dir.normalized();
        poses.push_back(delta * T);
    }
    return poses;
}

// Largest error of every pose relative to the fixed scan, against the truth.
PoseDifference max_relative_error(const std::vector<Pose>& truth, const std::vector<Pose>& est,
                                  std::size_t fixed) {
    PoseDifference worst;
    for (std::size_t s = 0; s < truth.size(); ++s) {
        const PoseDifference e =
            pose_difference(truth[fixed].inverse() * truth[s], est[fixed].inverse() * est[s]);
        worst.rotation_deg = std::max(worst.rotation_deg, e.rotation_deg);
        worst.translation_m = std::max(worst.translation_m, e.translation_m);
    }
    return worst;
}

class MultiviewRefinement : public ::testing::Test {
protected:
    void SetUp() override {
        scene_ = make_scene();
        links_ = make_links(scene_);
        initial_ = perturbed(scene_.T_world_scan_truth, 11);
    }
    Scene scene_;
    std::vector<MultiviewLink> links_;
    std::vector<Pose> initial_;
};

TEST_F(MultiviewRefinement, RecoversTruePosesFromOneDegreeTwoMillimetres) {
    ASSERT_GE(links_.size(), 12u);
    const MultiviewRefinementResult r = refine_multiview(initial_, links_, {});
    const PoseDifference e = max_relative_error(scene_.T_world_scan_truth, r.T_world_scan, 0);
    std::printf("%zu links, %s, %d rounds, max error %.2e deg %.2e mm, %.1f ms\n", links_.size(),
                std::string(to_string(r.status)).c_str(), r.rounds, e.rotation_deg,
                e.translation_m * 1e3, r.time_s * 1e3);
    EXPECT_EQ(r.status, MultiviewStatus::kConverged);
    EXPECT_LT(e.rotation_deg, 0.01);
    EXPECT_LT(e.translation_m, 0.00002);
    for (const MultiviewLinkReport& link : r.links) {
        EXPECT_FALSE(link.dropped);
        EXPECT_GT(link.rms_before_m, 1e-4);
        EXPECT_LT(link.rms_after_m, 1e-7);
    }
}

// Signs of v_k(X) - v_j(X): the one free scan is the source of its link in one case and the
// target in the other; a wrong sign would diverge in either.
TEST_F(MultiviewRefinement, ConvergesWithTheFreeScanAsSourceOrTarget) {
    const std::vector<MultiviewLink> one_link{
        make_link(scene_, 0, 6, scene_.T_world_scan_truth[6])};
    const std::vector<Pose> poses{initial_[0], initial_[1], initial_[2], initial_[3],
                                  initial_[4], initial_[5], initial_[6]};
    for (const std::size_t fixed : {std::size_t{0}, std::size_t{6}}) {
        const MultiviewRefinementResult r =
            refine_multiview(poses, one_link, {.fixed_scan_index = fixed});
        const std::size_t free_scan = fixed == 0 ? 6 : 0;
        const PoseDifference e = pose_difference(
            scene_.T_world_scan_truth[fixed].inverse() * scene_.T_world_scan_truth[free_scan],
            r.T_world_scan[fixed].inverse() * r.T_world_scan[free_scan]);
        EXPECT_LT(e.rotation_deg, 0.01) << "fixed " << fixed;
        EXPECT_LT(e.translation_m, 0.00002) << "fixed " << fixed;
        EXPECT_LT(r.rounds, 8) << "fixed " << fixed;
        EXPECT_EQ(r.disconnected_scans.size(), 5u);
    }
}

TEST_F(MultiviewRefinement, DropsABiasedLinkAndStillRecoversTheTruth) {
    // Link (1, 4) as a pairwise registration that ended 3° and 5 mm off.
    const Pose wrong = Eigen::Translation3d(0.005, -0.002, 0.001) *
                       Eigen::AngleAxisd(3.0 * kDeg, Eigen::Vector3d(0.3, 1, 0.2).normalized()) *
                       scene_.T_world_scan_truth[4];
    std::vector<MultiviewLink> links = links_;
    std::size_t bad = links.size();
    for (std::size_t l = 0; l < links.size(); ++l) {
        if (links[l].target_index == 1 && links[l].source_index == 4) bad = l;
    }
    ASSERT_LT(bad, links.size());
    links[bad] = make_link(scene_, 1, 4, wrong);
    const MultiviewRefinementResult r = refine_multiview(initial_, links, {});
    const PoseDifference e = max_relative_error(scene_.T_world_scan_truth, r.T_world_scan, 0);
    std::printf(
        "biased link: %s, %d rounds, dropped in round %d (rms %.2f mm), error %.2e deg "
        "%.2e mm\n",
        std::string(to_string(r.status)).c_str(), r.rounds, r.links[bad].dropped_in_round,
        r.links[bad].rms_after_m * 1e3, e.rotation_deg, e.translation_m * 1e3);
    EXPECT_EQ(r.status, MultiviewStatus::kConverged);
    for (std::size_t l = 0; l < links.size(); ++l) EXPECT_EQ(r.links[l].dropped, l == bad) << l;
    EXPECT_LT(e.rotation_deg, 0.01);
    EXPECT_LT(e.translation_m, 0.00002);
}

TEST_F(MultiviewRefinement, ReportsAScanWithoutLinksAsDisconnected) {
    std::vector<Pose> poses = initial_;
    std::mt19937 rng(3);
    poses.push_back(random_pose(rng, 1.0, 0.5));
    const MultiviewRefinementResult r = refine_multiview(poses, links_, {});
    EXPECT_EQ(r.status, MultiviewStatus::kDisconnected);
    EXPECT_TRUE(r.converged);
    EXPECT_EQ(r.disconnected_scans, std::vector<std::size_t>{8});
    EXPECT_TRUE(r.T_world_scan[8].matrix() == poses[8].matrix());
    poses.pop_back();
    std::vector<Pose> connected(r.T_world_scan.begin(), r.T_world_scan.end() - 1);
    const PoseDifference e = max_relative_error(scene_.T_world_scan_truth, connected, 0);
    EXPECT_LT(e.rotation_deg, 0.01);
    EXPECT_LT(e.translation_m, 0.00002);
}

TEST_F(MultiviewRefinement, FixedScanStaysExactlyFixed) {
    const MultiviewRefinementResult r = refine_multiview(initial_, links_, {.fixed_scan_index = 3});
    EXPECT_TRUE(r.T_world_scan[3].matrix() == initial_[3].matrix());
    const PoseDifference e = max_relative_error(scene_.T_world_scan_truth, r.T_world_scan, 3);
    EXPECT_LT(e.rotation_deg, 0.01);
    EXPECT_LT(e.translation_m, 0.00002);
}

TEST_F(MultiviewRefinement, IdenticalAcrossRunsAndSolvers) {
    const MultiviewRefinementResult a = refine_multiview(initial_, links_, {});
    const MultiviewRefinementResult b = refine_multiview(initial_, links_, {});
    const MultiviewRefinementResult sparse =
        refine_multiview(initial_, links_, {.max_dense_scans = 0});
    EXPECT_EQ(sparse.status, MultiviewStatus::kConverged);
    for (std::size_t s = 0; s < initial_.size(); ++s) {
        EXPECT_TRUE(a.T_world_scan[s].matrix() == b.T_world_scan[s].matrix()) << s;
        const PoseDifference e = pose_difference(a.T_world_scan[s], sparse.T_world_scan[s]);
        EXPECT_LT(e.rotation_deg, 1e-6) << s;
        EXPECT_LT(e.translation_m, 1e-9) << s;
    }
}

TEST_F(MultiviewRefinement, PlanarOverlapIsUnderconstrained) {
    MultiviewLink plane{.target_index = 0, .source_index = 1, .correspondences = {}};
    for (int i = 0; i < 400; ++i) {
        const Eigen::Vector3d p(0.01 * (i % 20), 0.01 * (i / 20), 0.0);
        plane.correspondences.push_back({p, p, Eigen::Vector3f::UnitZ(), 0.0, 1.0});
    }
    const std::vector<Pose> poses{Pose::Identity(), Pose::Identity()};
    const std::vector<MultiviewLink> links{plane};
    const MultiviewRefinementResult r = refine_multiview(poses, links, {});
    EXPECT_EQ(r.status, MultiviewStatus::kUnderconstrained);
    EXPECT_TRUE(r.T_world_scan[1].matrix().allFinite());
}

TEST_F(MultiviewRefinement, RejectsInvalidInputWithoutThrowing) {
    std::vector<MultiviewLink> links = links_;
    links.front().source_index = 99;
    const MultiviewRefinementResult r = refine_multiview(initial_, links, {});
    EXPECT_EQ(r.status, MultiviewStatus::kInvalidInput);
    EXPECT_EQ(r.T_world_scan.size(), initial_.size());
    EXPECT_EQ(refine_multiview({}, {}, {}).status, MultiviewStatus::kInvalidInput);
    EXPECT_EQ(refine_multiview(initial_, links_, {.fixed_scan_index = 8}).status,
              MultiviewStatus::kInvalidInput);
}

}  // namespace
}  // namespace anascan
