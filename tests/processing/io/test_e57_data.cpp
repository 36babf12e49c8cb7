// The real E57 sample in ../shared/data (label `data`): the pump scan of the E57 reference
// project, 155,201 points with intensity and colour on a 1074 x 345 grid.
#include <gtest/gtest.h>

#include <filesystem>

#include "anascan/processing/io/e57.hpp"

namespace anascan::io {
namespace {

namespace fs = std::filesystem;

const fs::path kPump =
    fs::path(ANASCAN_SHARED_DATA_DIR) / "e57-pump-laser-scan/pumpAVisualReferenceImage.e57";

TEST(E57Data, PumpMatchesItsReadme) {
    if (!fs::exists(kPump)) GTEST_SKIP() << "shared data absent: " << kPump << " not found";
    const auto file = read_e57(kPump);
    ASSERT_TRUE(file) << file.error().message;
    ASSERT_EQ(file->scans.size(), 1u);
    EXPECT_EQ(file->image_count, 1u);
    const E57Scan& s = file->scans[0];
    EXPECT_EQ(s.name, "pumpA");
    EXPECT_EQ(s.record_count, 155201u);
    EXPECT_EQ(s.scan.cloud.size(), 155201u);
    EXPECT_EQ(s.scan.cloud.intensity.size(), 155201u);
    EXPECT_EQ(s.scan.cloud.colors.size(), 155201u);
    EXPECT_FALSE(s.scan.meta.T_world_scan.has_value());  // the file has no pose element
    const Bounds b = local_bounds(s.scan.cloud);
    const Eigen::Vector3f lo = b.min + s.scan.cloud.origin_m.cast<float>();
    const Eigen::Vector3f hi = b.max + s.scan.cloud.origin_m.cast<float>();
    // README: x -2.90..1.72, y -5.30..-0.79, z -1.90..1.84 m (two decimals).
    EXPECT_NEAR(lo.x(), -2.90, 0.005);
    EXPECT_NEAR(hi.x(), 1.72, 0.005);
    EXPECT_NEAR(lo.y(), -5.30, 0.005);
    EXPECT_NEAR(hi.y(), -0.79, 0.005);
    EXPECT_NEAR(lo.z(), -1.90, 0.005);
    EXPECT_NEAR(hi.z(), 1.84, 0.005);
    EXPECT_EQ(s.grid.rows, 1074);
    EXPECT_EQ(s.grid.cols, 345);
    std::size_t filled = 0;
    for (const std::int32_t i : s.grid.point_index) filled += i != RangeGrid::kNoSample;
    EXPECT_EQ(filled, 155201u);  // one record per cell
}

TEST(E57Data, PumpWrittenByUsReadsBackBitForBit) {
    if (!fs::exists(kPump)) GTEST_SKIP() << "shared data absent: " << kPump << " not found";
    const auto file = read_e57(kPump);
    ASSERT_TRUE(file) << file.error().message;
    const auto bytes = encode_e57(file->scans);
    ASSERT_TRUE(bytes) << bytes.error().message;
    const auto again = parse_e57(*bytes, "pump-ours.e57");
    ASSERT_TRUE(again) << again.error().message;
    const E57Scan& a = file->scans[0];
    const E57Scan& b = again->scans[0];
    EXPECT_EQ(a.scan.cloud.positions, b.scan.cloud.positions);
    EXPECT_EQ(a.scan.cloud.intensity, b.scan.cloud.intensity);
    EXPECT_EQ(a.scan.cloud.colors, b.scan.cloud.colors);
    EXPECT_EQ(a.grid.point_index, b.grid.point_index);
}

}  // namespace
}  // namespace anascan::io
