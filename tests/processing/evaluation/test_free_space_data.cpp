// The free-space check on true poses of real scans: every bunny pair overlapping at the
// bun.conf poses (at least 10% of the source points within 2 mm of the target) is checked
// at its true pose in both directions, the Cyberware sensor taken at (0, 0, 1) m in each
// scan frame (it looks along -z from above the data; it sweeps a laser sheet, so a central
// projection is an approximation). True pairs must not be rejected. Skips when
// ../shared/data is absent.
#include <gtest/gtest.h>

#include <algorithm>
#include <cstdio>
#include <filesystem>
#include <string>
#include <vector>

#include "anascan/processing/evaluation/free_space.hpp"
#include "anascan/processing/evaluation/scan_agreement.hpp"
#include "anascan/processing/io/ply.hpp"
#include "anascan/processing/io/stanford_conf.hpp"
#include "anascan/processing/spatial/kdtree.hpp"

namespace anascan {
namespace {

namespace fs = std::filesystem;

const fs::path kBunnyDir = fs::path(ANASCAN_SHARED_DATA_DIR) / "stanford-bunny-range-scans/data";

struct Scan {
    PointCloud cloud;
    Pose T_world_scan;
};

TEST(FreeSpaceBunny, TruePairsAreNotRejected) {
    if (!fs::exists(kBunnyDir / "bun.conf")) {
        GTEST_SKIP() << "Stanford bunny scans not found at " << kBunnyDir;
    }
    auto conf = io::read_conf(kBunnyDir / "bun.conf");
    ASSERT_TRUE(conf.has_value()) << conf.error().message;
    std::vector<Scan> scans;
    std::vector<std::string> names;
    for (const io::ConfEntry& entry : conf->entries) {
        auto ply = io::read_ply(kBunnyDir / entry.file);
        ASSERT_TRUE(ply.has_value()) << ply.error().message;
        scans.push_back({std::move(ply->cloud), entry.T_world_scan});
        names.push_back(entry.file);
    }
    const Eigen::Vector3d sensor(0.0, 0.0, 1.0);
    const FreeSpaceConfig config;
    int checked = 0;
    double worst = 0.0;
    for (std::size_t t = 0; t < scans.size(); ++t) {
        const KdTree tree(scans[t].cloud.positions);
        for (std::size_t s = 0; s < scans.size(); ++s) {
            if (s == t) continue;
            const Pose T = scans[t].T_world_scan.inverse() * scans[s].T_world_scan;
            const PointCloud moved = transformed(scans[s].cloud, T);
            const PairAgreement overlap =
                measure_agreement(moved, scans[t].cloud, tree, {.overlap_radius_m = 0.002});
            if (overlap.overlap_fraction < 0.1) continue;
            const FreeSpaceResult r =
                check_free_space(scans[t].cloud, sensor, 0.0, scans[s].cloud, T, config);
            ASSERT_TRUE(r.valid);
            std::printf("%s in %s's view: overlap %.2f, %zu of %zu in view, %.4f in free space\n",
                        names[s].c_str(), names[t].c_str(), overlap.overlap_fraction, r.in_view,
                        r.samples, r.violation_fraction);
            ++checked;
            worst = std::max(worst, r.violation_fraction);
            if (r.in_view >= config.min_points_in_view) {
                EXPECT_LE(r.violation_fraction, config.max_violation_fraction)
                    << names[s] << " onto " << names[t];
            }
        }
    }
    std::printf("%d directed pairs checked, worst violation fraction %.4f\n", checked, worst);
    EXPECT_GT(checked, 20);
}

}  // namespace
}  // namespace anascan
