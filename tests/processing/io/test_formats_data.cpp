// Format readers on the real Stanford bunny files in ../shared/data (label `data`);
// each test skips with a message when the shared data is absent.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <filesystem>
#include <numbers>

#include "anascan/processing/io/ply.hpp"
#include "anascan/processing/io/stanford_conf.hpp"
#include "test_quaternion_util.hpp"

namespace anascan::io {
namespace {

namespace fs = std::filesystem;

using testing_util::hamilton_rotation;

TEST(ConfData, BunnyConfMatchesTheDocumentedConvention) {
    const fs::path path =
        fs::path(ANASCAN_SHARED_DATA_DIR) / "stanford-bunny-range-scans/data/bun.conf";
    if (!fs::exists(path)) GTEST_SKIP() << "shared data absent: " << path << " not found";
    const auto conf = read_conf(path);
    ASSERT_TRUE(conf.has_value()) << conf.error().message;
    ASSERT_EQ(conf->entries.size(), 10u);
    ASSERT_TRUE(conf->camera.has_value());
    EXPECT_EQ(conf->entries[0].file, "bun000.ply");
    EXPECT_TRUE(conf->entries[0].T_world_scan.matrix().isIdentity(0.0));
    // bmesh bun045.ply -0.0520211 -0.000383981 -0.0109223 0.00548449 -0.294635 -0.0038555 0.955586
    const ConfEntry* bun045 = conf->find("bun045.ply");
    ASSERT_NE(bun045, nullptr);
    const Eigen::Matrix3d R = hamilton_rotation(0.00548449, -0.294635, -0.0038555, 0.955586);
    EXPECT_LT((bun045->T_world_scan.linear() - R.transpose()).cwiseAbs().maxCoeff(), 1e-12);
    EXPECT_TRUE(bun045->T_world_scan.translation().isApprox(
        Eigen::Vector3d(-0.0520211, -0.000383981, -0.0109223)));
    // The scanner turned the bunny about +y by ~34 degrees: p_world = R^T p rotates by +34.
    const Eigen::AngleAxisd aa(bun045->T_world_scan.linear());
    EXPECT_NEAR(aa.angle() * 180.0 / std::numbers::pi, 34.27, 0.05);
    EXPECT_GT(aa.axis().y(), 0.999);
}

TEST(PlyRealData, Bun000HasVerticesAndRangeGrid) {
    const fs::path path =
        fs::path(ANASCAN_SHARED_DATA_DIR) / "stanford-bunny-range-scans/data/bun000.ply";
    if (!fs::exists(path)) GTEST_SKIP() << "shared data absent: " << path;
    const Expected<PlyData> read = read_ply(path);
    ASSERT_TRUE(read) << read.error().message;
    EXPECT_EQ(read->format, PlyFormat::kAscii);
    EXPECT_EQ(read->cloud.size(), 40256u);
    EXPECT_FALSE(read->cloud.has_normals());
    ASSERT_TRUE(read->grid.has_value());
    EXPECT_EQ(read->grid->rows, 400);
    EXPECT_EQ(read->grid->cols, 512);
    std::size_t samples = 0;
    for (std::size_t i = 0; i < read->grid->point_index.size(); ++i) {
        const std::int32_t index = read->grid->point_index[i];
        if (index == RangeGrid::kNoSample) continue;
        EXPECT_EQ(index, static_cast<std::int32_t>(samples));  // Stanford order: row-major
        ++samples;
    }
    EXPECT_EQ(samples, 40256u);
    const Bounds bounds = local_bounds(read->cloud);
    EXPECT_LT(bounds.extent().maxCoeff(), 0.3f);  // a bunny, in metres
    EXPECT_GT(bounds.extent().maxCoeff(), 0.05f);
}

}  // namespace
}  // namespace anascan::io
