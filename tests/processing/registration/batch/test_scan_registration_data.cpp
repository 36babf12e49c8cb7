// register_scans on the ten Stanford bunny scans, each moved by a random rigid transform
// (uniform rotation, up to 0.5 m translation, three fixed seeds) and given in shuffled order, then
// compared with bun.conf by evaluate_poses (both in the frame of the first scan found in
// both). Normals are estimated and oriented toward (0,0,1) m in each scan's own frame (the
// Cyberware sensor looks along +z), as in test_global_registration_data.cpp; the moved
// clouds carry the moved sensor position. Translation is compared at each scan's frame
// origin after undoing the random move (the bun.conf frames, within ~0.1 m of the data).
// Asserted: all ten placed within 0.5° and 1 mm. Skips when ../shared/data is absent.
#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <algorithm>
#include <cstdio>
#include <filesystem>
#include <random>
#include <string>
#include <vector>

#include "anascan/processing/evaluation/pose_evaluation.hpp"
#include "anascan/processing/evaluation/pose_sampling.hpp"
#include "anascan/processing/io/ply.hpp"
#include "anascan/processing/io/stanford_conf.hpp"
#include "anascan/processing/registration/batch/scan_registration.hpp"

namespace anascan {
namespace {

namespace fs = std::filesystem;

const fs::path kBunnyDir = fs::path(ANASCAN_SHARED_DATA_DIR) / "stanford-bunny-range-scans/data";

/// A bunny scan moved by T_moved_scan: loaded lazily, sensor at the moved (0,0,1) m.
ScanInput moved_scan(const std::string& file, const Pose& T_moved_scan) {
    const fs::path path = kBunnyDir / file;
    return {.name = file,
            .load = [path, T_moved_scan]() -> Expected<PointCloud> {
                auto ply = io::read_ply(path);
                if (!ply) return fail(ply.error());
                return transformed(ply->cloud, T_moved_scan);
            },
            .sensor_origin_scan_m = T_moved_scan* Eigen::Vector3d(0.0, 0.0, 1.0)};
}

class ScanRegistrationBunny : public ::testing::TestWithParam<unsigned> {};

TEST_P(ScanRegistrationBunny, TenMovedShuffledScansArePlaced) {
    if (!fs::exists(kBunnyDir / "bun.conf")) {
        GTEST_SKIP() << "Stanford bunny scans not found at " << kBunnyDir
                     << " (they come with ../shared/data beside the checkout)";
    }
    auto conf = io::read_conf(kBunnyDir / "bun.conf");
    ASSERT_TRUE(conf.has_value()) << conf.error().message;
    std::vector<io::ConfEntry> entries = conf->entries;
    std::mt19937 rng(GetParam());
    std::shuffle(entries.begin(), entries.end(), rng);
    std::vector<ScanInput> inputs;
    std::vector<Pose> T_moved_scan;
    for (const io::ConfEntry& entry : entries) {
        T_moved_scan.push_back(sample_random_pose(rng, 0.5));
        inputs.push_back(moved_scan(entry.file, T_moved_scan.back()));
    }

    const ScanRegistrationResult result = register_scans(inputs, {}, {});

    // Estimated pose of the original scan frame: T_world_moved · T_moved_scan.
    std::vector<NamedPose> estimated;
    for (std::size_t i = 0; i < entries.size(); ++i) {
        const ScanOutcome& scan = result.scans[i];
        if (!scan.placed)
            std::printf("%s not placed: %s\n", scan.name.c_str(), scan.reason.c_str());
        if (scan.placed) estimated.push_back({scan.name, scan.T_world_scan * T_moved_scan[i]});
    }
    std::vector<NamedPose> truth;
    for (const io::ConfEntry& e : conf->entries) truth.push_back({e.file, e.T_world_scan});
    const auto evaluation = evaluate_poses(estimated, truth);
    ASSERT_TRUE(evaluation.has_value());
    const ScanRegistrationTimings& t = result.timings;
    std::printf(
        "placed %zu of %zu, %zu groups, %zu verified pairs of %zu, %zu links (%zu dropped); "
        "max error %.4f deg, %.4f mm (reference %s)\n"
        "times: prepare %.1f s, features %.1f s, matching %.1f s, pairwise %.1f s, graph %.3f s, "
        "fine %.1f s, multiview %.2f s, total %.1f s\n",
        result.placed_count, result.scans.size(), result.group_count, result.verified_pair_count,
        result.pairs.size(), result.link_count, result.dropped_link_count,
        evaluation->max_rotation_deg, 1e3 * evaluation->max_translation_m,
        evaluation->reference.c_str(), t.prepare_s, t.features_s, t.matching_s, t.pairwise_s,
        t.pose_graph_s, t.fine_s, t.multiview_s, t.total_s);
    EXPECT_EQ(evaluation->placed, 10u);
    EXPECT_LT(evaluation->max_rotation_deg, 0.5);
    EXPECT_LT(evaluation->max_translation_m, 0.001);
}

INSTANTIATE_TEST_SUITE_P(Seeds, ScanRegistrationBunny, ::testing::Values(20261122u, 7u, 2024u));

}  // namespace
}  // namespace anascan
