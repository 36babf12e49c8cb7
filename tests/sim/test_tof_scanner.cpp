#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>

#include "anascan/sim/tof_scanner.hpp"
#include "anascan/sim/viewpoints.hpp"
#include "sim_test_scenes.hpp"

namespace anascan::sim {
namespace {

class TofScannerTest : public ::testing::Test {
protected:
    static void SetUpTestSuite() {
        scene_ = new Scene(testing::small_scene());
        caster_ = new RayCaster(testing::caster_of(scene_->mesh));
    }
    static void TearDownTestSuite() {
        delete caster_;
        delete scene_;
    }
    static Pose scanner_pose() {
        return tripod_pose(scene_->T_world_block.translation(), 40.0, 3.0, 1.5);
    }
    static TofScanResult scan(const TofScannerConfig& config) {
        return simulate_tof_scan(*caster_, triangle_albedos(*scene_), scanner_pose(), config)
            .value();
    }
    static TofScannerConfig coarse() {
        return TofScannerConfig{.angular_step_deg = 0.25, .seed = 5};
    }

    static inline Scene* scene_ = nullptr;
    static inline RayCaster* caster_ = nullptr;
};

// Range along each point's own ray to the ground-truth mesh (re-cast), per point.
std::vector<double> true_ranges(const RayCaster& caster, const TofScanResult& r) {
    const Pose& T = *r.scan.meta.T_world_scan;
    std::vector<double> ranges;
    for (const Eigen::Vector3f& p : r.scan.cloud.positions) {
        const auto hit = caster.cast(T.translation(), T.linear() * p.cast<double>().normalized());
        ranges.push_back(hit ? hit->distance_m : NAN);
    }
    return ranges;
}

TEST_F(TofScannerTest, RangeRmsAgainstTheMeshIsTheConfiguredNoise) {
    const TofScanResult r = scan(coarse());
    const std::vector<double> truth = true_ranges(*caster_, r);
    double sum2 = 0.0;
    std::size_t n = 0;
    for (std::size_t i = 0; i < truth.size(); ++i) {
        if (r.mixed[i]) continue;
        ASSERT_TRUE(std::isfinite(truth[i]));
        const double e = r.scan.cloud.positions[i].cast<double>().norm() - truth[i];
        sum2 += e * e;
        ++n;
    }
    ASSERT_GT(n, 100000u);
    const double rms = std::sqrt(sum2 / n);
    std::printf("range RMS %.3f mm over %zu points (configured 7 mm)\n", 1000 * rms, n);
    EXPECT_NEAR(rms, 0.007, 0.2 * 0.007);
}

TEST_F(TofScannerTest, MixedPixelsLieBetweenTheSurfacesOfADepthEdge) {
    TofScannerConfig config = coarse();
    config.range_noise_sigma_m = 0.0;
    config.mixed_pixel_probability = 1.0;
    const TofScanResult r = scan(config);
    std::size_t mixed = 0;
    for (std::size_t i = 0; i < r.mixed.size(); ++i) {
        const double measured = r.scan.cloud.positions[i].cast<double>().norm();
        if (!r.mixed[i]) {
            ASSERT_NEAR(measured, r.true_range_m[i], 1e-5);
            continue;
        }
        ++mixed;
        EXPECT_GT(std::abs(measured - r.true_range_m[i]), 0.0);
    }
    std::printf("%zu mixed pixels of %zu points\n", mixed, r.mixed.size());
    EXPECT_GT(mixed, 100u);  // Block silhouette, tent corners.
    EXPECT_LT(mixed, r.mixed.size() / 20);
    // Each mixed point lies off every surface: not on the mesh along its ray.
    const std::vector<double> truth = true_ranges(*caster_, r);
    std::size_t floating = 0;
    for (std::size_t i = 0; i < r.mixed.size(); ++i) {
        if (r.mixed[i] &&
            std::abs(r.scan.cloud.positions[i].cast<double>().norm() - truth[i]) > 0.01)
            ++floating;
    }
    EXPECT_GT(floating, mixed / 2);
}

TEST_F(TofScannerTest, GridMetadataAndPoseDescribeThePanorama) {
    TofScannerConfig config = coarse();
    config.min_range_m = 3.2;
    const TofScanResult r = scan(config);
    EXPECT_EQ(r.grid.cols, 1440);  // 360 / 0.25.
    EXPECT_EQ(r.grid.rows, 321);   // 80 / 0.25 + 1.
    EXPECT_EQ(r.scan.meta.device_kind, DeviceKind::kTimeOfFlight);
    EXPECT_TRUE(r.scan.meta.T_world_scan->isApprox(scanner_pose(), 0.0));
    EXPECT_EQ(*r.scan.meta.sensor_origin_scan_m, Eigen::Vector3d::Zero());
    EXPECT_EQ(r.scan.cloud.intensity.size(), r.scan.cloud.size());
    std::size_t seen = 0;
    for (int row = 0; row < r.grid.rows; ++row) {
        for (int col = 0; col < r.grid.cols; col += 7) {
            const std::int32_t i = r.grid.at(row, col);
            if (i == RangeGrid::kNoSample) continue;
            ++seen;
            const Eigen::Vector3d p = r.scan.cloud.positions[i].cast<double>();
            EXPECT_NEAR(std::asin(p.z() / p.norm()) * 180 / M_PI, 40.0 - 0.25 * row, 1e-3);
            EXPECT_GE(p.norm(), 3.2);
        }
    }
    EXPECT_GT(seen, 10000u);
}

TEST_F(TofScannerTest, SameSeedSameScanOtherSeedOtherNoise) {
    TofScannerConfig config = coarse();
    config.angular_step_deg = 1.0;
    const TofScanResult a = scan(config), b = scan(config);
    EXPECT_EQ(a.scan.cloud.positions, b.scan.cloud.positions);
    config.seed = 6;
    const TofScanResult c = scan(config);
    EXPECT_NE(c.scan.cloud.positions, a.scan.cloud.positions);
}

TEST_F(TofScannerTest, InvalidSettingsAreErrors) {
    const auto albedos = triangle_albedos(*scene_);
    EXPECT_EQ(simulate_tof_scan(*caster_, albedos, scanner_pose(), {.angular_step_deg = 0.0})
                  .error()
                  .code,
              ErrorCode::kInvalidArgument);
    EXPECT_FALSE(simulate_tof_scan(*caster_, albedos, scanner_pose(),
                                   {.elevation_min_deg = 10, .elevation_max_deg = -10})
                     .has_value());
    EXPECT_FALSE(simulate_tof_scan(*caster_, albedos, scanner_pose(), {.angular_step_deg = 0.0001})
                     .has_value());
}

}  // namespace
}  // namespace anascan::sim
