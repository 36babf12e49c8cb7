// Coverage of a simulated structured-light session (reduced resolution, so it runs in
// seconds): the estimate from the scans agrees with the ground-truth mesh's coverage, and
// before the stone is turned over its resting face is reported as a hole.

#include <gtest/gtest.h>

#include <memory>

#include "coverage_session.hpp"

namespace anascan::sim::test {
namespace {

// The rig at half resolution: 320 x 240 cameras, 1.9 mm per pixel at 1 m.
CoverageSessionConfig small_session() {
    CoverageSessionConfig config{.views = 8, .flip_after = 4};
    config.rig = {.camera_width_px = 320,
                  .camera_height_px = 240,
                  .camera_focal_px = 540.0,
                  .projector_width_px = 256,
                  .projector_height_px = 160,
                  .projector_focal_px = 340.0};
    return config;
}

// Density threshold scaled with the rig: a quarter of the full rig's points.
const CoverageConfig kConfig{.min_density_per_cm2 = 5.0};

class CoverageSessionTest : public ::testing::Test {
protected:
    static void SetUpTestSuite() {
        auto session = simulate_coverage_session(small_session());
        ASSERT_TRUE(session) << session.error().message;
        session_ = std::make_unique<CoverageSession>(std::move(*session));
    }
    static void TearDownTestSuite() { session_.reset(); }
    static std::unique_ptr<CoverageSession> session_;
};
std::unique_ptr<CoverageSession> CoverageSessionTest::session_;

TEST_F(CoverageSessionTest, EstimateAgreesWithGroundTruthAfterTheFlip) {
    const auto views = coverage_views(*session_, session_->scans.size());
    const CoverageReport estimate = compute_coverage(views, kConfig);
    const CoverageReport truth =
        compute_coverage_on_surface(session_->stone_world0, views, kConfig);
    ASSERT_EQ(estimate.status, CoverageStatus::kOk) << estimate.message;
    ASSERT_EQ(truth.status, CoverageStatus::kOk) << truth.message;
    EXPECT_GT(truth.fraction, 0.8);  // every face was seen
    EXPECT_NEAR(estimate.fraction, truth.fraction, 0.02);
    EXPECT_NEAR(estimate.surface_area_m2, truth.surface_area_m2, 0.05 * truth.surface_area_m2);
}

TEST_F(CoverageSessionTest, BeforeTheFlipTheRestingFaceIsAHole) {
    const auto views = coverage_views(*session_, 4);
    const CoverageReport estimate = compute_coverage(views, kConfig);
    const CoverageReport truth =
        compute_coverage_on_surface(session_->stone_world0, views, kConfig);
    ASSERT_EQ(estimate.status, CoverageStatus::kOk) << estimate.message;
    EXPECT_NEAR(estimate.fraction, truth.fraction, 0.02);
    ASSERT_FALSE(estimate.holes.empty());
    // The block rests on its -z face (0.45 x 0.4 m) on the ground z = 0 of the first world.
    const CoverageHole& bottom = estimate.holes[0];
    EXPECT_LT(bottom.normal.z(), -0.95);
    EXPECT_GT(bottom.area_m2, 0.8 * 0.45 * 0.4);
    EXPECT_LT(bottom.centre_m.z(), 0.02);
}

}  // namespace
}  // namespace anascan::sim::test
