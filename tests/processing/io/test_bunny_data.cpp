// The ten real Stanford bunny range scans placed with bun.conf must agree where they
// overlap; a scan moved off its true pose must not. Skips when ../shared/data is absent.
#include <gtest/gtest.h>

#include <filesystem>
#include <vector>

#include "anascan/processing/core/pose.hpp"
#include "anascan/processing/evaluation/scan_agreement.hpp"
#include "anascan/processing/io/ply.hpp"
#include "anascan/processing/io/stanford_conf.hpp"
#include "anascan/processing/spatial/kdtree.hpp"

namespace anascan {
namespace {

namespace fs = std::filesystem;

const fs::path kBunnyDir = fs::path(ANASCAN_SHARED_DATA_DIR) / "stanford-bunny-range-scans/data";

struct PlacedScans {
    std::vector<std::string> names;
    std::vector<PointCloud> clouds;  // In the bun.conf frame.
};

class BunnyData : public ::testing::Test {
protected:
    static void SetUpTestSuite() {
        if (!fs::exists(kBunnyDir / "bun.conf")) return;
        auto conf = io::read_conf(kBunnyDir / "bun.conf");
        ASSERT_TRUE(conf.has_value()) << conf.error().message;
        scans_ = new PlacedScans;
        for (const io::ConfEntry& entry : conf->entries) {
            auto ply = io::read_ply(kBunnyDir / entry.file);
            ASSERT_TRUE(ply.has_value()) << ply.error().message;
            scans_->names.push_back(entry.file);
            scans_->clouds.push_back(transformed(ply->cloud, entry.T_world_scan));
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
    static PlacedScans* scans_;
};

PlacedScans* BunnyData::scans_ = nullptr;

// Overlap = a neighbour within 5 mm (about ten sample spacings), so a misalignment of a
// millimetre or more shows in the distances instead of only shrinking the overlap.
constexpr AgreementConfig kAgreement{.overlap_radius_m = 0.005, .max_samples = 4000};
// Pairs overlapping less than this are dominated by the rims of the scans, where
// point-to-point distances measure sampling at grazing angles rather than alignment.
constexpr double kMinOverlap = 0.4;

TEST_F(BunnyData, AllTenScansLoadWithTheirPoses) {
    ASSERT_EQ(scans_->clouds.size(), 10u);
    std::size_t total = 0;
    for (const PointCloud& c : scans_->clouds) total += c.size();
    EXPECT_EQ(total, 362272u);  // Point counts listed in the data's README.
}

TEST_F(BunnyData, OverlappingScansAgreeBelowOneMillimetre) {
    std::vector<KdTree> trees;
    for (const PointCloud& c : scans_->clouds) trees.emplace_back(c.positions);
    int overlapping_pairs = 0;
    for (std::size_t i = 0; i < trees.size(); ++i) {
        for (std::size_t j = 0; j < trees.size(); ++j) {
            if (i == j) continue;
            const PairAgreement a =
                measure_agreement(scans_->clouds[i], scans_->clouds[j], trees[j], kAgreement);
            if (a.overlap_fraction < kMinOverlap) continue;
            ++overlapping_pairs;
            EXPECT_LT(a.median_distance_m, 0.001) << scans_->names[i] << " vs " << scans_->names[j]
                                                  << ": overlap " << a.overlap_fraction;
        }
    }
    EXPECT_GE(overlapping_pairs, 20);  // Ten scans around the bunny overlap widely.
}

TEST_F(BunnyData, AScanOffItsPoseDisagrees) {
    // Negative control: the same measure must notice a 2 mm / 1 degree error.
    const Pose T_error =
        make_pose(Eigen::Quaterniond(Eigen::AngleAxisd(M_PI / 180.0, Eigen::Vector3d::UnitY())),
                  Eigen::Vector3d(0.002, 0.0, 0.0));
    const PointCloud moved = transformed(scans_->clouds[1], T_error);  // bun045
    const KdTree tree0(scans_->clouds[0].positions);                   // bun000
    const PairAgreement a = measure_agreement(moved, scans_->clouds[0], tree0, kAgreement);
    ASSERT_GT(a.overlap_fraction, kMinOverlap);
    EXPECT_GT(a.median_distance_m, 0.001);
}

}  // namespace
}  // namespace anascan
