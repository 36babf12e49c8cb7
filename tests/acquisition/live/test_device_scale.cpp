// The live session's lengths from the device's own scan: measured spacing and noise, and the
// lengths raised to them (a terrestrial scanner's 7 mm) or left as they are (a
// structured-light head's 0.1 mm).
#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <random>

#include "anascan/acquisition/live/device_scale.hpp"

namespace anascan::acquisition {
namespace {

/// A 1 m × 1 m plane sampled on a grid of `spacing_m`, noise of `noise_m` along its normal.
PointCloud noisy_plane(double spacing_m, double noise_m, std::uint64_t seed) {
    std::mt19937_64 rng(seed);
    std::normal_distribution<double> along_normal(0.0, noise_m);
    PointCloud cloud;
    const int n = static_cast<int>(1.0 / spacing_m);
    for (int i = 0; i < n; ++i)
        for (int j = 0; j < n; ++j)
            cloud.positions.emplace_back(static_cast<float>(i * spacing_m),
                                         static_cast<float>(j * spacing_m),
                                         static_cast<float>(along_normal(rng)));
    return cloud;
}

TEST(DeviceScale, TheNoiseAndSpacingOfAScanAreMeasuredOnItsOwnPoints) {
    for (const auto& [spacing_m, noise_m] : {std::pair{0.006, 0.007}, std::pair{0.0004, 0.0001}}) {
        const DeviceScale scale = measure_device_scale(noisy_plane(spacing_m, noise_m, 7));
        EXPECT_GT(scale.samples, 1000u);
        // Neighbours found in 3-D lie near the point's height where the noise is as large
        // as the spacing: a little of the noise goes unseen there.
        EXPECT_GT(scale.noise_m, 0.8 * noise_m) << spacing_m;
        EXPECT_LT(scale.noise_m, 1.15 * noise_m) << spacing_m;
        EXPECT_GE(scale.spacing_m, spacing_m * 0.999) << spacing_m;
    }
}

TEST(DeviceScale, NonFiniteAndTooFewPointsMeasureNothing) {
    PointCloud few = noisy_plane(0.25, 0.001, 1);  // 16 points.
    few.positions.resize(15);
    EXPECT_EQ(measure_device_scale(few).samples, 0u);
    PointCloud with_nan = noisy_plane(0.01, 0.001, 2);
    with_nan.positions[5] = Eigen::Vector3f::Constant(std::numeric_limits<float>::quiet_NaN());
    const DeviceScale scale = measure_device_scale(with_nan);
    EXPECT_GT(scale.samples, 0u);
    EXPECT_TRUE(std::isfinite(scale.noise_m));
}

TEST(DeviceScale, ATerrestrialScannersNoiseRaisesTheLengthsAStructuredLightHeadsLeavesThem) {
    const LiveRegistrationConfig given{};
    const LiveRegistrationConfig head =
        lengths_for_device(given, {.spacing_m = 0.0004, .noise_m = 0.0001, .samples = 2000});
    EXPECT_EQ(head.prepare.voxel_size_m, given.prepare.voxel_size_m);
    EXPECT_EQ(head.hypotheses.fine.overlap_distance_m, given.hypotheses.fine.overlap_distance_m);
    EXPECT_EQ(head.links.fine.max_correspondence_distance_m,
              given.links.fine.max_correspondence_distance_m);
    EXPECT_EQ(head.votes.displacement_m, given.votes.displacement_m);

    const double noise_m = 0.007;
    const LiveRegistrationConfig tof =
        lengths_for_device(given, {.spacing_m = 0.006, .noise_m = noise_m, .samples = 2000});
    EXPECT_DOUBLE_EQ(tof.prepare.voxel_size_m, 3.0 * noise_m);
    EXPECT_GE(tof.prepare.ground_band_m, 3.0 * noise_m);
    for (const FineRegistrationConfig* fine :
         {&tof.hypotheses.fine, &tof.links.fine, &tof.global.registration.fine}) {
        EXPECT_GE(fine->overlap_distance_m, 3.0 * noise_m);
        EXPECT_GE(fine->min_correspondence_distance_m, 3.0 * noise_m);
        EXPECT_GT(fine->max_correspondence_distance_m, fine->min_correspondence_distance_m);
    }
    // Lengths of the operator's motion are not the device's: they keep their values.
    EXPECT_EQ(tof.hypotheses.slide_probe_m, given.hypotheses.slide_probe_m);
    EXPECT_EQ(tof.hypotheses.max_prior_correction_m, given.hypotheses.max_prior_correction_m);
}

TEST(DeviceScale, TheRegistrarAdoptsTheLengthsOfItsFirstUsableScanOnlyWhenAsked) {
    PointCloud box_side = noisy_plane(0.006, 0.007, 3);
    {
        LiveRegistrar off;
        const LiveDecision d = off.add({.seq = 1, .cloud = box_side});
        EXPECT_EQ(d.message.find("device:"), std::string::npos) << d.message;
    }
    LiveRegistrar on({.lengths_from_device = true});
    // An empty scan measures nothing: the next usable one sets the lengths.
    EXPECT_EQ(on.add({.seq = 1, .cloud = {}}).method, LiveMethod::kUnusable);
    const LiveDecision d = on.add({.seq = 2, .cloud = box_side});
    EXPECT_NE(d.message.find("device: spacing"), std::string::npos) << d.message;
    EXPECT_NE(d.message.find("lengths raised to it"), std::string::npos) << d.message;
    const LiveDecision again = on.add({.seq = 3, .cloud = box_side});
    EXPECT_EQ(again.message.find("device:"), std::string::npos) << again.message;
}

}  // namespace
}  // namespace anascan::acquisition
