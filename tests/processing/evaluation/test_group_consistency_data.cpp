// The group consistency check on real scans at their true poses: the ten bunny scans at
// the bun.conf poses (reduced to about 20 000 points, normals by k-NN PCA with unknown sign,
// no sensor position) must agree. Skips when ../shared/data is absent.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <filesystem>
#include <string>
#include <vector>

#include "anascan/processing/cleaning/normals.hpp"
#include "anascan/processing/evaluation/group_consistency.hpp"
#include "anascan/processing/features/integral_invariants.hpp"
#include "anascan/processing/io/ply.hpp"
#include "anascan/processing/io/stanford_conf.hpp"
#include "anascan/processing/spatial/voxel_grid.hpp"

namespace anascan {
namespace {

namespace fs = std::filesystem;

const fs::path kBunnyDir = fs::path(ANASCAN_SHARED_DATA_DIR) / "stanford-bunny-range-scans/data";

TEST(GroupConsistencyBunny, TheTruePosesAgree) {
    if (!fs::exists(kBunnyDir / "bun.conf")) {
        GTEST_SKIP() << "Stanford bunny scans not found at " << kBunnyDir;
    }
    auto conf = io::read_conf(kBunnyDir / "bun.conf");
    ASSERT_TRUE(conf.has_value()) << conf.error().message;
    std::vector<PointCloud> clouds;
    std::vector<std::string> names;
    for (const io::ConfEntry& entry : conf->entries) {
        auto ply = io::read_ply(kBunnyDir / entry.file);
        ASSERT_TRUE(ply.has_value()) << ply.error().message;
        const double spacing = median_sample_spacing_m(ply->cloud);
        const double ratio = std::max(1.0, static_cast<double>(ply->cloud.size()) / 20000.0);
        PointCloud reduced =
            voxel_downsample(ply->cloud, {.voxel_size_m = spacing * std::sqrt(ratio)});
        reduced.normals.clear();
        estimate_normals(reduced, {});
        clouds.push_back(std::move(reduced));
        names.push_back(entry.file);
    }
    std::vector<ConsistencyScan> scans;
    for (std::size_t i = 0; i < clouds.size(); ++i)
        scans.push_back({.cloud = &clouds[i], .T_group_scan = conf->entries[i].T_world_scan});
    const GroupConsistency g = check_group_consistency(scans, {});
    for (const PairConsistency& p : g.pairs)
        std::printf(
            "%s - %s: near %zu, crossing %.3f (> %.1f), median %.2f deg, offset %.3f mm "
            "(noise %.3f): %s\n",
            names[p.a].c_str(), names[p.b].c_str(), p.near_samples, p.crossing_fraction,
            p.crossing_angle_deg, p.median_normal_angle_deg, p.median_offset_m * 1e3,
            p.noise_m * 1e3, p.agrees ? "agrees" : p.reason.c_str());
    EXPECT_GT(g.pairs.size(), 20u);
    EXPECT_TRUE(g.consistent);
    EXPECT_TRUE(g.take_out.empty());
}

}  // namespace
}  // namespace anascan
