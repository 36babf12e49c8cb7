// Fine registration of the real Stanford bunny pair bun045 → bun000 from starts 5° and
// 5 mm off the bun.conf alignment, in several directions: it must end within 0.1° and
// 0.1 mm of bun.conf. (bun.conf is a multi-view alignment: the pairwise point-to-plane
// optimum of this pair lies ~0.08° from it for Open3D with all points too, so 0.05° is
// out of reach for any pairwise method; see docs/fine-registration.md.) Skips when
// ../shared/data is absent.
#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <cstdio>
#include <filesystem>
#include <numbers>
#include <vector>

#include "anascan/processing/core/pose.hpp"
#include "anascan/processing/io/ply.hpp"
#include "anascan/processing/io/stanford_conf.hpp"
#include "anascan/processing/registration/fine/fine_registration.hpp"
#include "test_normals_util.hpp"

namespace anascan {
namespace {

namespace fs = std::filesystem;

const fs::path kBunnyDir = fs::path(ANASCAN_SHARED_DATA_DIR) / "stanford-bunny-range-scans/data";

struct BunnyPair {
    PointCloud source;  // bun045, its scan frame, with normals.
    PointCloud target;  // bun000, its scan frame, with normals.
    Pose T_target_source_truth;
};

class FineRegistrationBunny : public ::testing::Test {
protected:
    static void SetUpTestSuite() {
        if (!fs::exists(kBunnyDir / "bun.conf")) return;
        auto conf = io::read_conf(kBunnyDir / "bun.conf");
        ASSERT_TRUE(conf.has_value()) << conf.error().message;
        const io::ConfEntry* e000 = conf->find("bun000.ply");
        const io::ConfEntry* e045 = conf->find("bun045.ply");
        ASSERT_TRUE(e000 != nullptr && e045 != nullptr);
        auto target = io::read_ply(kBunnyDir / "bun000.ply");
        auto source = io::read_ply(kBunnyDir / "bun045.ply");
        ASSERT_TRUE(target.has_value()) << target.error().message;
        ASSERT_TRUE(source.has_value()) << source.error().message;
        pair_ = new BunnyPair{std::move(source->cloud), std::move(target->cloud),
                              e000->T_world_scan.inverse() * e045->T_world_scan};
        // The Cyberware scanner looks from +z of each scan frame (see test_normals_util).
        test::estimate_normals_pca(pair_->target, Eigen::Vector3f::UnitZ());
        test::estimate_normals_pca(pair_->source, Eigen::Vector3f::UnitZ());
    }
    static void TearDownTestSuite() {
        delete pair_;
        pair_ = nullptr;
    }
    void SetUp() override {
        if (pair_ == nullptr) {
            GTEST_SKIP() << "Stanford bunny scans not found at " << kBunnyDir
                         << " (they come with ../shared/data beside the checkout)";
        }
    }
    static BunnyPair* pair_;
};

BunnyPair* FineRegistrationBunny::pair_ = nullptr;

// The truth moved by `angle_deg` about `axis` through the source's centroid and by
// `shift_m` along `direction`, all in the target frame.
Pose perturbed(const BunnyPair& pair, const Eigen::Vector3d& axis, double angle_deg,
               const Eigen::Vector3d& direction, double shift_m) {
    Eigen::Vector3d centroid = Eigen::Vector3d::Zero();
    for (const Eigen::Vector3f& p : pair.source.positions) centroid += p.cast<double>();
    centroid = pair.T_target_source_truth * (centroid / pair.source.size());
    const Eigen::AngleAxisd turn(angle_deg * std::numbers::pi / 180.0, axis.normalized());
    return Eigen::Translation3d(shift_m * direction.normalized()) * Eigen::Translation3d(centroid) *
           turn * Eigen::Translation3d(-centroid) * pair.T_target_source_truth;
}

TEST_F(FineRegistrationBunny, Bun045OntoBun000EndsAtConfPoseFromFiveDegreesFiveMillimetres) {
    const std::vector<std::pair<Eigen::Vector3d, Eigen::Vector3d>> starts{
        {{1, 0, 0}, {0, 1, 0}},  {{0, 1, 0}, {0, 0, 1}},  {{0, 0, 1}, {1, 0, 0}},
        {{1, 1, 0}, {-1, 0, 1}}, {{0, -1, 1}, {1, 1, 1}}, {{-1, 1, 1}, {0, -1, -1}},
    };
    for (const auto& [axis, direction] : starts) {
        const Pose initial = perturbed(*pair_, axis, 5.0, direction, 0.005);
        const FineRegistrationResult r =
            register_fine(pair_->source, pair_->target, initial, FineRegistrationConfig{});
        const PoseDifference error =
            pose_difference(pair_->T_target_source_truth, r.T_target_source);
        std::printf(
            "axis (%g %g %g): %s, %d iterations, error %.4f deg %.4f mm, rms %.3f mm, "
            "overlap %.2f, normal deviation %.2f deg, degeneracy %.3g, %.1f ms\n",
            axis.x(), axis.y(), axis.z(), std::string(to_string(r.status)).c_str(), r.iterations,
            error.rotation_deg, error.translation_m * 1e3, r.rms_m * 1e3, r.overlap_fraction,
            r.normal_deviation_deg.value_or(-1.0), r.degeneracy.eigenvalue_ratio, r.time_s * 1e3);
        EXPECT_EQ(r.status, FineRegistrationStatus::kConverged) << r.message;
        EXPECT_LT(error.rotation_deg, 0.1);
        EXPECT_LT(error.translation_m, 0.0001);
        EXPECT_GT(r.overlap_fraction, 0.3);
    }
}

TEST_F(FineRegistrationBunny, KeepsCorrespondencesForMultiView) {
    const Pose initial = perturbed(*pair_, {1, 0, 0}, 2.0, {0, 1, 0}, 0.002);
    const FineRegistrationResult r =
        register_fine(pair_->source, pair_->target, initial, {.keep_correspondences = true});
    ASSERT_EQ(r.status, FineRegistrationStatus::kConverged) << r.message;
    EXPECT_EQ(r.correspondences.size(), r.inlier_count);
    EXPECT_GT(r.inlier_count, 1000u);
}

}  // namespace
}  // namespace anascan
