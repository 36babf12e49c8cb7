// register_scans on three overlapping windows of a bumpy surface (known poses, normals
// given, each window in a random frame): all placed within 0.5° and 1 mm of the truth relative to
// the first view (translation at the view's centroid: the frames sit up to 0.5 m from the data); an
// unrelated shape (a hemisphere), an empty scan and a scan that fails to load are reported not
// placed with a reason.
#include <gtest/gtest.h>
#include <unistd.h>

#include <Eigen/Geometry>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <limits>
#include <random>
#include <string>
#include <vector>

#include "anascan/processing/evaluation/pose_sampling.hpp"
#include "anascan/processing/registration/batch/scan_registration.hpp"
#include "test_bumpy_surface.hpp"

namespace anascan {
namespace {

using testing_util::Bump;
using testing_util::random_bumps;

/// The bumpy height field on a 1 mm grid over x in [x_min, x_max] (object frame).
PointCloud bumpy_window(const std::vector<Bump>& bumps, double x_min, double x_max,
                        double offset_m) {
    return testing_util::bumpy_surface(bumps, x_min, x_max, 0.001, offset_m);
}

/// Upper half of a sphere of radius 0.05 m, ~1 mm apart, outward normals: no shape in
/// common with the bumpy windows.
PointCloud hemisphere() {
    PointCloud cloud;
    const int n = 31400;  // Points on the whole sphere.
    const double golden = 3.14159265358979 * (3.0 - std::sqrt(5.0));
    for (int i = 0; i < n / 2; ++i) {
        const double z = 1.0 - 2.0 * (i + 0.5) / n;
        const double r = std::sqrt(1.0 - z * z);
        const Eigen::Vector3f u(float(r * std::cos(golden * i)), float(r * std::sin(golden * i)),
                                float(z));
        cloud.positions.push_back(0.05f * u);
        cloud.normals.push_back(u);
    }
    return cloud;
}

struct SyntheticScan {
    ScanInput input;
    Pose T_object_scan;  // Truth.
    Eigen::Vector3d centroid_scan_m;
};

/// `object` (object frame) expressed in a random scan frame; the sensor 1 m above (+z).
SyntheticScan make_view(const PointCloud& object, std::mt19937& rng, const std::string& name) {
    const Pose T_scan_object = sample_random_pose(rng, 0.5);
    PointCloud cloud = transformed(object, T_scan_object);
    Eigen::Vector3d centroid = Eigen::Vector3d::Zero();
    for (std::size_t i = 0; i < cloud.size(); ++i) centroid += cloud.world_position(i);
    centroid /= static_cast<double>(cloud.size());
    const Eigen::Vector3d sensor = T_scan_object * Eigen::Vector3d(0.0, 0.0, 1.0);
    return {.input = {.name = name,
                      .load = [cloud] { return Expected<PointCloud>(cloud); },
                      .sensor_origin_scan_m = sensor},
            .T_object_scan = T_scan_object.inverse(),
            .centroid_scan_m = centroid};
}

/// Adds Gaussian noise of `sigma_m` along z (object frame) to every point.
PointCloud with_noise(PointCloud cloud, double sigma_m, std::uint32_t seed) {
    std::mt19937 rng(seed);
    std::normal_distribution<float> noise(0.0f, static_cast<float>(sigma_m));
    for (Eigen::Vector3f& p : cloud.positions) p.z() += noise(rng);
    return cloud;
}

// Four windows that fit each other closely and one that fits them only ~0.5 mm RMS (within
// the pairwise verification's limit of one 1 mm spacing, like a look-alike pose): the
// session RMS gate leaves the fifth out and says why; without the gate it is placed.
TEST(ScanRegistration, SessionRmsGateLeavesOutAPoorlyFittingScan) {
    std::mt19937 rng(7);
    const std::vector<Bump> bumps = random_bumps(11, 14);
    std::vector<ScanInput> inputs;
    for (int k = 0; k < 5; ++k) {
        PointCloud window = bumpy_window(bumps, -0.1 + 0.03 * k, 0.0 + 0.03 * k, 0.0003 * k);
        if (k == 4) window = with_noise(std::move(window), 0.0005, 3);
        inputs.push_back(make_view(window, rng, "view" + std::to_string(k)).input);
    }
    const ScanRegistrationResult gated = register_scans(inputs, {}, {});
    EXPECT_EQ(gated.placed_count, 4u);
    EXPECT_FALSE(gated.scans[4].placed);
    EXPECT_NE(gated.scans[4].reason.find("session RMS gate"), std::string::npos)
        << gated.scans[4].reason;
    EXPECT_GT(gated.gated_pair_count, 0u);
    EXPECT_LT(gated.session_rms_gate_m, 0.0005);

    const ScanRegistrationResult ungated =
        register_scans(inputs, {.session_rms_gate_factor = 0.0}, {});
    EXPECT_EQ(ungated.placed_count, 5u);
    EXPECT_TRUE(std::isinf(ungated.session_rms_gate_m));
}

TEST(ScanRegistration, PlacesViewsAndReportsTheOthers) {
    std::mt19937 rng(20261122);
    std::vector<SyntheticScan> views;
    const std::vector<Bump> bumps = random_bumps(7, 14);
    for (int k = 0; k < 3; ++k) {
        const PointCloud window = bumpy_window(bumps, -0.1 + 0.04 * k, 0.02 + 0.04 * k, 0.0003 * k);
        views.push_back(make_view(window, rng, "view" + std::to_string(k)));
    }
    std::vector<ScanInput> inputs;
    for (const SyntheticScan& v : views) inputs.push_back(v.input);
    inputs.push_back(make_view(hemisphere(), rng, "unrelated").input);
    inputs.push_back({.name = "empty", .load = [] { return Expected<PointCloud>(PointCloud{}); }});
    inputs.push_back({.name = "unreadable",
                      .load = [] { return Expected<PointCloud>(fail(ErrorCode::kIo, "gone")); }});

    const ScanRegistrationResult result = register_scans(inputs, {}, {});

    ASSERT_EQ(result.scans.size(), inputs.size());
    EXPECT_EQ(result.placed_count, views.size());
    EXPECT_EQ(result.reference_scan, 0u);
    for (std::size_t i = 0; i < views.size(); ++i) {
        const ScanOutcome& scan = result.scans[i];
        ASSERT_TRUE(scan.placed) << scan.name << ": " << scan.reason;
        const Pose truth = views[0].T_object_scan.inverse() * views[i].T_object_scan;
        const Pose estimate = result.scans[0].T_world_scan.inverse() * scan.T_world_scan;
        const PoseDifference error = pose_difference(estimate, truth);
        const Eigen::Vector3d c = views[i].centroid_scan_m;
        EXPECT_LT(error.rotation_deg, 0.5) << scan.name;
        EXPECT_LT((estimate * c - truth * c).norm(), 0.001) << scan.name;
    }
    for (std::size_t i = views.size(); i < inputs.size(); ++i) {
        EXPECT_FALSE(result.scans[i].placed) << result.scans[i].name;
        EXPECT_FALSE(result.scans[i].reason.empty()) << result.scans[i].name;
    }
    EXPECT_EQ(result.scans[4].group, -1);
    EXPECT_NE(result.scans[5].reason.find("gone"), std::string::npos);
    EXPECT_GE(result.link_count, 2u);
    EXPECT_GT(result.timings.total_s, 0.0);
}

/// `count` windows 0.08 m long, 0.024 m apart, along a strip of `bumps` random bumps (seed
/// 3), each in a random frame (`seed`), named window0, window1, ...
std::vector<SyntheticScan> strip_views(int count, int bumps, unsigned seed) {
    std::mt19937 rng(seed);
    const std::vector<Bump> strip = random_bumps(3, bumps);
    std::vector<SyntheticScan> views;
    for (int k = 0; k < count; ++k) {
        const double x = -0.1 + 0.024 * k;
        views.push_back(make_view(bumpy_window(strip, x, x + 0.08, 0.0002 * k), rng,
                                  "window" + std::to_string(k)));
    }
    return views;
}

// The scale code paths on a small strip: pair pruning (2 candidates per scan) and the
// out-of-core store (clouds and sites spilled, at most 2 in memory) place every window as
// accurately as before, match fewer than all pairs, reload from disk and clean up.
TEST(ScanRegistration, PrunedAndSpilledStripIsPlaced) {
    const std::vector<SyntheticScan> views = strip_views(6, 60, 5);
    std::vector<ScanInput> inputs;
    for (int k : {3, 0, 5, 1, 4, 2}) inputs.push_back(views[std::size_t(k)].input);  // Shuffled.
    const std::filesystem::path spill =
        std::filesystem::temp_directory_path() / ("anascan_test_spill_" + std::to_string(getpid()));
    const ScanRegistrationResult result = register_scans(inputs,
                                                         {.max_candidates_per_scan = 2,
                                                          .spill_directory = spill,
                                                          .max_loaded_clouds = 2,
                                                          .max_link_correspondences = 200},
                                                         {});
    EXPECT_TRUE(result.spill_error.empty()) << result.spill_error;
    EXPECT_EQ(result.placed_count, inputs.size());
    EXPECT_LT(result.pairs.size(), inputs.size() * (inputs.size() - 1) / 2);
    EXPECT_GT(result.cloud_reloads, 0u);
    const std::size_t ref = result.reference_scan;
    const SyntheticScan& ref_view = views[std::size_t(std::stoi(result.scans[ref].name.substr(6)))];
    for (const ScanOutcome& scan : result.scans) {
        ASSERT_TRUE(scan.placed) << scan.name << ": " << scan.reason;
        const SyntheticScan& view = views[std::size_t(std::stoi(scan.name.substr(6)))];
        const Pose truth = ref_view.T_object_scan.inverse() * view.T_object_scan;
        const Pose estimate = result.scans[ref].T_world_scan.inverse() * scan.T_world_scan;
        const Eigen::Vector3d c = view.centroid_scan_m;
        EXPECT_LT(pose_difference(estimate, truth).rotation_deg, 0.5) << scan.name;
        EXPECT_LT((estimate * c - truth * c).norm(), 0.001) << scan.name;
    }
    EXPECT_TRUE(!std::filesystem::exists(spill) || std::filesystem::is_empty(spill));
    std::filesystem::remove_all(spill);
}

// Bridging: with two candidates per scan the pruned pairs of a strip of eight windows leave
// two groups; the bridging rounds join them (no pair of non-overlapping windows is
// verified), every window is placed, within 0.5° and 1 mm of its neighbour.
TEST(ScanRegistration, BridgingJoinsTheGroupsLeftByPruning) {
    const std::vector<SyntheticScan> views = strip_views(8, 80, 11);
    std::vector<ScanInput> inputs;
    for (int k : {3, 6, 0, 5, 1, 7, 4, 2}) inputs.push_back(views[std::size_t(k)].input);
    ScanRegistrationConfig config{.max_candidates_per_scan = 2, .max_link_correspondences = 200};
    config.bridge_rounds = 0;
    const ScanRegistrationResult pruned = register_scans(inputs, config, {});
    config.bridge_rounds = 4;
    const ScanRegistrationResult bridged = register_scans(inputs, config, {});
    std::printf("pruned: placed %zu groups %zu; bridged: placed %zu groups %zu, %zu bridge pairs\n",
                pruned.placed_count, pruned.group_count, bridged.placed_count, bridged.group_count,
                bridged.bridge_pair_count);
    EXPECT_GT(pruned.group_count, 1u);
    EXPECT_EQ(bridged.placed_count, inputs.size());
    EXPECT_GT(bridged.bridge_pair_count, 0u);
    for (const PairOutcome& p : bridged.pairs) {
        const int a = std::stoi(bridged.scans[p.source].name.substr(6));
        const int b = std::stoi(bridged.scans[p.target].name.substr(6));
        EXPECT_TRUE(std::abs(a - b) <= 3 || !p.verified) << a << " " << b;
    }
    // Between neighbouring windows (along the strip the error adds up: 0.6° at the far end
    // of these small windows even with every pair matched).
    std::vector<std::size_t> input_of(views.size());
    for (std::size_t i = 0; i < bridged.scans.size(); ++i) {
        input_of[std::size_t(std::stoi(bridged.scans[i].name.substr(6)))] = i;
    }
    for (std::size_t k = 0; k + 1 < views.size(); ++k) {
        const ScanOutcome& a = bridged.scans[input_of[k]];
        const ScanOutcome& b = bridged.scans[input_of[k + 1]];
        const Pose truth = views[k + 1].T_object_scan.inverse() * views[k].T_object_scan;
        const Pose estimate = b.T_world_scan.inverse() * a.T_world_scan;
        const Eigen::Vector3d c = views[k].centroid_scan_m;
        EXPECT_LT(pose_difference(estimate, truth).rotation_deg, 0.5) << a.name;
        EXPECT_LT((estimate * c - truth * c).norm(), 0.001) << a.name;
    }
}

/// A loader returning a fixed cloud.
ScanInput fixed_scan(const std::string& name, PointCloud cloud) {
    return {.name = name, .load = [cloud] { return Expected<PointCloud>(cloud); }};
}

PointCloud repeated_point(std::size_t count, const Eigen::Vector3f& p) {
    PointCloud cloud;
    cloud.positions.assign(count, p);
    return cloud;
}

TEST(ScanRegistration, BadScansGetOneClearReasonEachAndCopiesAWarning) {
    std::mt19937 rng(11);
    const std::vector<Bump> bumps = random_bumps(7, 14);
    const SyntheticScan a = make_view(bumpy_window(bumps, -0.1, 0.02, 0.0), rng, "a");
    const SyntheticScan b = make_view(bumpy_window(bumps, -0.06, 0.06, 0.0003), rng, "b");
    const float nan = std::numeric_limits<float>::quiet_NaN();
    std::vector<ScanInput> inputs{a.input, b.input, a.input};
    inputs[2].name = "copy of a";
    inputs.push_back(fixed_scan("all nan", repeated_point(500, {nan, nan, nan})));
    inputs.push_back(fixed_scan("duplicates", repeated_point(2000, {0.1f, 0.2f, 0.3f})));
    inputs.push_back(
        fixed_scan("few", select(*a.input.load(), std::vector<std::size_t>{0, 1, 2, 3, 200})));
    inputs.push_back(fixed_scan("empty", PointCloud{}));

    const ScanRegistrationResult result = register_scans(inputs, {}, {});

    ASSERT_EQ(result.scans.size(), inputs.size());
    for (std::size_t i = 0; i < 3; ++i) {
        EXPECT_TRUE(result.scans[i].placed)
            << result.scans[i].name << ": " << result.scans[i].reason;
    }
    EXPECT_TRUE(result.scans[0].warning.empty());
    EXPECT_NE(result.scans[2].warning.find("the same points as a"), std::string::npos)
        << result.scans[2].warning;
    const auto reason_has = [&](std::size_t i, const std::string& words) {
        EXPECT_FALSE(result.scans[i].placed) << result.scans[i].name;
        EXPECT_NE(result.scans[i].reason.find(words), std::string::npos)
            << result.scans[i].name << ": " << result.scans[i].reason;
    };
    reason_has(3, "all 500 points are non-finite");
    reason_has(4, "no normal could be estimated");
    reason_has(5, "only 5 usable points");
    reason_has(6, "empty scan");
}

TEST(ScanRegistration, NoScansIsAnEmptyResult) {
    const ScanRegistrationResult result = register_scans({}, {}, {});
    EXPECT_TRUE(result.scans.empty());
    EXPECT_EQ(result.placed_count, 0u);
}

TEST(ScanRegistration, PrepareOrientsNormalsTowardTheSensor) {
    std::mt19937 rng(7);
    SyntheticScan view = make_view(bumpy_window(random_bumps(7, 14), -0.1, 0.0, 0.0), rng, "v");
    PointCloud cloud = *view.input.load();
    cloud.normals.clear();
    ASSERT_GT(prepare_scan(cloud, view.input.sensor_origin_scan_m, {}), 1000u);
    std::size_t facing = 0;
    for (std::size_t i = 0; i < cloud.size(); ++i) {
        const Eigen::Vector3d to_sensor =
            *view.input.sensor_origin_scan_m - cloud.world_position(i);
        facing += cloud.normals[i].cast<double>().dot(to_sensor) >= 0.0;
    }
    EXPECT_EQ(facing, cloud.size());
}

}  // namespace
}  // namespace anascan
