// Global registration of real Stanford bunny scan pairs (see docs/global-registration.md).
// Every ordered pair with at least 40% overlap at the bun.conf poses (fraction of source
// points with a target point within 2 mm) is registered after moving the source by a random
// rigid transform (uniform rotation, up to 0.5 m translation, fixed seed); a result is
// correct within 0.5° and 1 mm of T_target_source = T_world_target⁻¹ · T_world_source, the
// translation measured at the source centroid. Goal of the issue, asserted: ≥ 95% of the
// overlapping pairs correct, ≤ 1% of all pairs accepted with a wrong pose (measured: 41 of
// 42 correct, none wrong; see docs/global-registration.md).
// Pairs with less overlap (10–40%) are run too, to count wrong poses accepted. Skips when
// ../shared/data is absent.
#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <algorithm>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <random>
#include <string>
#include <vector>

#include "anascan/processing/cleaning/normals.hpp"
#include "anascan/processing/evaluation/pose_sampling.hpp"
#include "anascan/processing/evaluation/scan_agreement.hpp"
#include "anascan/processing/io/ply.hpp"
#include "anascan/processing/io/stanford_conf.hpp"
#include "anascan/processing/registration/global/global_registration.hpp"

namespace anascan {
namespace {

namespace fs = std::filesystem;

const fs::path kBunnyDir = fs::path(ANASCAN_SHARED_DATA_DIR) / "stanford-bunny-range-scans/data";

struct Scan {
    std::string name;
    PointCloud cloud;  // Scan frame, normals toward the scanner (+z).
    Pose T_world_scan;
};

struct Tally {
    int pairs = 0, correct = 0, accepted = 0, wrong_accepted = 0;
    double total_time_s = 0.0, max_time_s = 0.0;
};

class GlobalRegistrationBunny : public ::testing::Test {
protected:
    static void SetUpTestSuite() {
        if (!fs::exists(kBunnyDir / "bun.conf")) return;
        auto conf = io::read_conf(kBunnyDir / "bun.conf");
        ASSERT_TRUE(conf.has_value()) << conf.error().message;
        scans_ = new std::vector<Scan>;
        for (const io::ConfEntry& entry : conf->entries) {
            auto ply = io::read_ply(kBunnyDir / entry.file);
            ASSERT_TRUE(ply.has_value()) << ply.error().message;
            Scan scan{entry.file, std::move(ply->cloud), entry.T_world_scan};
            estimate_normals(scan.cloud, {});
            // The Cyberware scanner looks along the scan frame's +z toward the sensor.
            orient_toward(scan.cloud, Eigen::Vector3f(0.0f, 0.0f, 1.0f));
            scans_->push_back(std::move(scan));
        }
    }
    static void TearDownTestSuite() {
        delete scans_;
        scans_ = nullptr;
    }
    void SetUp() override {
        if (scans_ == nullptr) {
            GTEST_SKIP() << "Stanford bunny scans not found at " << kBunnyDir
                         << " (they come with ../shared/data beside the checkout)";
        }
    }
    static std::vector<Scan>* scans_;
};

std::vector<Scan>* GlobalRegistrationBunny::scans_ = nullptr;

Eigen::Vector3d centroid_m(const PointCloud& cloud) {
    Eigen::Vector3d sum = Eigen::Vector3d::Zero();
    for (const Eigen::Vector3f& p : cloud.positions) sum += p.cast<double>();
    return cloud.origin_m + sum / static_cast<double>(cloud.size());
}

double truth_overlap(const Scan& source, const Scan& target, const Pose& T_target_source) {
    const KdTree tree(target.cloud.positions);
    return measure_agreement(transformed(source.cloud, T_target_source), target.cloud, tree,
                             {.overlap_radius_m = 0.002, .max_samples = 5000})
        .overlap_fraction;
}

void register_pair(const Scan& source, const Scan& target, const Pose& T_target_source,
                   double overlap, std::mt19937& rng, Tally& tally) {
    const Pose T_moved_source = sample_random_pose(rng, 0.5);
    const Pose truth = T_target_source * T_moved_source.inverse();
    const PointCloud moved = transformed(source.cloud, T_moved_source);
    const GlobalRegistrationResult result = register_global(moved, target.cloud, {});
    const PoseDifference error = pose_difference(result.T_target_source, truth);
    // Translation error where the data is (the source centroid), not at the moved frame's
    // origin up to 0.5 m away, where 0.1° of rotation alone would move 0.9 mm.
    const double centroid_error_m =
        (result.T_target_source * centroid_m(moved) - truth * centroid_m(moved)).norm();
    const bool correct = error.rotation_deg < 0.5 && centroid_error_m < 0.001;
    const bool accepted = result.status == GlobalRegistrationStatus::kSuccess;
    ++tally.pairs;
    tally.correct += accepted && correct;
    tally.accepted += accepted;
    tally.wrong_accepted += accepted && !correct;
    tally.total_time_s += result.timing.total_s;
    tally.max_time_s = std::max(tally.max_time_s, result.timing.total_s);
    std::printf(
        "%-13s -> %-13s ov %.2f %-19s err %7.3f deg %8.2f mm (origin %8.2f mm)  hyp %zu  "
        "patches %zu/%zu  %.2f s\n",
        source.name.c_str(), target.name.c_str(), overlap,
        std::string(to_string(result.status)).c_str(), error.rotation_deg, 1e3 * centroid_error_m,
        1e3 * error.translation_m, result.hypotheses.size(), result.source_patches,
        result.target_patches, result.timing.total_s);
    if (std::getenv("ANASCAN_GLOBAL_VERBOSE") == nullptr) return;
    const GlobalRegistrationTiming& t = result.timing;
    std::printf(
        "  times: invariants %.3f patches %.3f matching %.3f refinement %.3f; cand %zu; "
        "radii %.1f-%.1f mm; target spacing %.2f mm\n",
        t.invariants_s, t.patches_s, t.matching_s, t.refinement_s, result.matching.candidate_count,
        1e3 * result.radii_m[0], 1e3 * result.radii_m[3], 1e3 * result.target_spacing_m);
    for (const HypothesisOutcome& h : result.hypotheses) {
        const PoseDifference e0 = pose_difference(h.hypothesis.T_target_source, truth);
        const PoseDifference e1 = pose_difference(h.fine.T_target_source, truth);
        std::printf(
            "  sites %.2f score %4.0f inl %3zu rms %5.1f mm  init %6.1f deg %6.1f mm -> %6.2f deg "
            "%6.1f mm  %s rms %.3f mm ov %.2f nd %.1f %s\n",
            h.site_overlap, h.hypothesis.score, h.hypothesis.inliers.size(),
            1e3 * h.hypothesis.rms_m, e0.rotation_deg, 1e3 * e0.translation_m, e1.rotation_deg,
            1e3 * e1.translation_m, std::string(to_string(h.fine.status)).c_str(),
            1e3 * h.fine.rms_m, h.fine.overlap_fraction, h.fine.normal_deviation_deg.value_or(-1.0),
            h.rejection.c_str());
    }
}

void print(const char* what, const Tally& tally) {
    std::printf(
        "%s: %d pairs, %d correct and accepted, %d accepted, %d wrong accepted, "
        "mean %.2f s, max %.2f s per pair\n",
        what, tally.pairs, tally.correct, tally.accepted, tally.wrong_accepted,
        tally.total_time_s / std::max(1, tally.pairs), tally.max_time_s);
}

TEST_F(GlobalRegistrationBunny, OverlappingPairsRegisterFromRandomPoses) {
    std::mt19937 rng(20240611);
    Tally overlapping, partial;
    for (const Scan& source : *scans_) {
        for (const Scan& target : *scans_) {
            if (&source == &target) continue;
            const Pose T_target_source = target.T_world_scan.inverse() * source.T_world_scan;
            const double overlap = truth_overlap(source, target, T_target_source);
            if (overlap < 0.1) continue;
            register_pair(source, target, T_target_source, overlap, rng,
                          overlap >= 0.4 ? overlapping : partial);
        }
    }
    print("overlap >= 40%", overlapping);
    print("overlap 10-40%", partial);
    ASSERT_GT(overlapping.pairs, 10);
    // Goal of the issue: >= 95% correct, <= 1% wrong accepted.
    EXPECT_GE(overlapping.correct, 0.95 * overlapping.pairs);
    EXPECT_LE(overlapping.wrong_accepted + partial.wrong_accepted,
              0.01 * (overlapping.pairs + partial.pairs));
}

}  // namespace
}  // namespace anascan
