#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <ostream>
#include <string>

#include "anascan/processing/io/text_points.hpp"

namespace anascan::io {
namespace {

using ::testing::HasSubstr;
namespace fs = std::filesystem;

std::span<const char> text_bytes(std::string_view text) { return {text.data(), text.size()}; }

PointCloud parsed_xyz(std::string_view text) {
    auto cloud = parse_xyz(text_bytes(text), "t.xyz");
    EXPECT_TRUE(cloud.has_value()) << cloud.error().message;
    return cloud ? *cloud : PointCloud{};
}

TEST(XyzParse, SeparatorsCommentsAndLineEndings) {
    const PointCloud cloud =
        parsed_xyz("# header\r\n1 2 3\r\n4,5,6\n\n  7\t8 ,9 // tail\n+1e-3 -2.5E1 .5");
    ASSERT_EQ(cloud.size(), 4u);
    EXPECT_TRUE(cloud.attributes_consistent());
    EXPECT_FALSE(cloud.has_normals() || cloud.has_colors() || cloud.has_intensity());
    EXPECT_EQ(cloud.positions[1], Eigen::Vector3f(4, 5, 6));
    EXPECT_EQ(cloud.positions[2], Eigen::Vector3f(7, 8, 9));
    EXPECT_EQ(cloud.positions[3], Eigen::Vector3f(1e-3f, -25.0f, 0.5f));
}

TEST(XyzParse, ColumnCountFixesTheLayout) {
    const PointCloud intensity = parsed_xyz("0 0 0 0.5\n1 1 1 0.25\n");
    ASSERT_EQ(intensity.intensity.size(), 2u);
    EXPECT_FLOAT_EQ(intensity.intensity[1], 0.25f);

    const PointCloud normals = parsed_xyz("0 0 0 0 0 1\n1 1 1 0.6 0.8 0\n");
    ASSERT_EQ(normals.normals.size(), 2u);
    EXPECT_TRUE(normals.colors.empty());
    EXPECT_EQ(normals.normals[1], Eigen::Vector3f(0.6f, 0.8f, 0.0f));

    const PointCloud rgb = parsed_xyz("0 0 0 255 128 0\n1 1 1 1 2 3\n");
    ASSERT_EQ(rgb.colors.size(), 2u);
    EXPECT_TRUE(rgb.normals.empty());
    EXPECT_EQ(rgb.colors[0], (Rgb8{255, 128, 0}));

    const PointCloud seven = parsed_xyz("0 0 0 0.5 10 20 30\n");
    EXPECT_EQ(seven.intensity.size(), 1u);
    EXPECT_EQ(seven.colors[0], (Rgb8{10, 20, 30}));

    const PointCloud nine = parsed_xyz("0 0 0 0 1 0 10 20 30\n");
    EXPECT_EQ(nine.normals[0], Eigen::Vector3f(0, 1, 0));
    EXPECT_EQ(nine.colors[0], (Rgb8{10, 20, 30}));
    EXPECT_TRUE(nine.attributes_consistent());
}

TEST(XyzParse, SiteCoordinatesKeepSubMillimetrePrecision) {
    const PointCloud cloud =
        parsed_xyz("500000.1234 4000000.5678 100.25\n500001.0001 4000002 99\n");
    ASSERT_EQ(cloud.size(), 2u);
    EXPECT_NEAR(cloud.world_position(0).x(), 500000.1234, 1e-5);
    EXPECT_NEAR(cloud.world_position(0).y(), 4000000.5678, 1e-5);
    EXPECT_NEAR(cloud.world_position(1).x(), 500001.0001, 1e-5);
    EXPECT_NEAR(cloud.world_position(1).z(), 99.0, 1e-5);
}

TEST(PtsParse, CountThenPointsWithIntensityAndColour) {
    const auto cloud = parse_pts(text_bytes("3\r\n1 2 3 -100 1 2 3\r\n4 5 6 0 4 5 6\r\n"
                                            "7 8 9 2047 7 8 9\r\n"),
                                 "scan.pts");
    ASSERT_TRUE(cloud.has_value()) << cloud.error().message;
    ASSERT_EQ(cloud->size(), 3u);
    EXPECT_EQ(cloud->positions[2], Eigen::Vector3f(7, 8, 9));
    EXPECT_FLOAT_EQ(cloud->intensity[0], -100.0f);
    EXPECT_EQ(cloud->colors[1], (Rgb8{4, 5, 6}));
    EXPECT_TRUE(cloud->attributes_consistent());
}

TEST(PtsParse, IntensityOnly) {
    const auto cloud = parse_pts(text_bytes("2\n1 2 3 4\n5 6 7 8"), "scan.pts");
    ASSERT_TRUE(cloud.has_value()) << cloud.error().message;
    EXPECT_EQ(cloud->intensity, (std::vector<float>{4, 8}));
    EXPECT_FALSE(cloud->has_colors());
}

TEST(TextPointsFile, ExtensionChoosesTheFormat) {
    const fs::path dir = fs::path(ANASCAN_BINARY_DIR) / "test-tmp" / "text_points";
    fs::create_directories(dir);
    std::ofstream(dir / "a.PTS") << "1\n1 2 3 4\n";
    std::ofstream(dir / "b.xyz") << "1 2 3 4\n";
    std::ofstream(dir / "c.obj") << "v 1 2 3\n";
    const auto pts = read_text_points(dir / "a.PTS");
    ASSERT_TRUE(pts.has_value()) << pts.error().message;
    EXPECT_EQ(pts->size(), 1u);
    const auto xyz = read_text_points(dir / "b.xyz");
    ASSERT_TRUE(xyz.has_value()) << xyz.error().message;
    EXPECT_EQ(xyz->intensity.size(), 1u);
    const auto obj = read_text_points(dir / "c.obj");
    ASSERT_FALSE(obj.has_value());
    EXPECT_EQ(obj.error().code, ErrorCode::kUnsupported);
    EXPECT_THAT(obj.error().message, HasSubstr("c.obj"));
    const auto missing = read_text_points(dir / "none.xyz");
    ASSERT_FALSE(missing.has_value());
    EXPECT_EQ(missing.error().code, ErrorCode::kIo);
}

struct BrokenText {
    const char* name;
    bool pts;
    const char* text;
    ErrorCode code;
    const char* line;
    const char* what;
};

// Shows the case name instead of the bytes in test output.
void PrintTo(const BrokenText& broken, std::ostream* os) { *os << broken.name; }

class TextPointsErrors : public ::testing::TestWithParam<BrokenText> {};

TEST_P(TextPointsErrors, NameSourceLineAndProblem) {
    const BrokenText& broken = GetParam();
    const std::string source = broken.pts ? "scan.pts" : "scan.xyz";
    const auto cloud = broken.pts ? parse_pts(text_bytes(broken.text), source)
                                  : parse_xyz(text_bytes(broken.text), source);
    ASSERT_FALSE(cloud.has_value()) << broken.name;
    EXPECT_EQ(cloud.error().code, broken.code) << cloud.error().message;
    EXPECT_THAT(cloud.error().message, HasSubstr(source + ": " + broken.line));
    EXPECT_THAT(cloud.error().message, HasSubstr(broken.what));
}

INSTANTIATE_TEST_SUITE_P(
    Kinds, TextPointsErrors,
    ::testing::Values(
        BrokenText{"XyzEmpty", false, "", ErrorCode::kEmpty, "line 1:", "without any point"},
        BrokenText{"XyzOnlyComments", false, "# a\n\n// b\n", ErrorCode::kEmpty,
                   "line 3:", "without any point"},
        BrokenText{"XyzNotANumber", false, "1 2 3\n1 abc 3\n", ErrorCode::kFormat,
                   "line 2:", "field 2 'abc' is not a number"},
        BrokenText{"XyzFieldCount", false, "1 2 3\n1 2 3\n1 2 3 4\n", ErrorCode::kFormat,
                   "line 3:", "expected 3 fields (as on line 1), found 4"},
        BrokenText{"XyzFiveColumns", false, "1 2 3 4 5\n", ErrorCode::kFormat,
                   "line 1:", "found 5"},
        BrokenText{"XyzNaN", false, "1 2 3\nnan 2 3\n", ErrorCode::kFormat,
                   "line 2:", "field 1 'nan' is not finite"},
        BrokenText{"XyzOverflow", false, "1 2 3\n1 2 1e39\n", ErrorCode::kFormat,
                   "line 2:", "too large for a float"},
        BrokenText{"XyzOutOfRange", false, "1 2 1e999\n", ErrorCode::kFormat,
                   "line 1:", "out of range"},
        BrokenText{"XyzColourRange", false, "0 0 0 0.5 1 2 3\n0 0 0 0.5 1 256 3\n",
                   ErrorCode::kFormat, "line 2:", "field 6 '256' is not a colour value 0-255"},
        BrokenText{"PtsEmpty", true, "\n\n", ErrorCode::kEmpty, "line 2:", "without any point"},
        BrokenText{"PtsZeroCount", true, "0\n", ErrorCode::kEmpty, "line 1:", "count is 0"},
        BrokenText{"PtsCountNotANumber", true, "three\n1 2 3 4\n", ErrorCode::kFormat,
                   "line 1:", "expected a whole number, found 'three'"},
        BrokenText{"PtsCountLineFields", true, "1 2 3 4\n", ErrorCode::kFormat,
                   "line 1:", "point count alone"},
        BrokenText{"PtsTruncated", true, "3\n1.000 2.000 3.000 4\n1.000 2.000 3.000 4\n",
                   ErrorCode::kTruncated,
                   "line 3:", "file ends after 2 of 3 points (count on line 1)"},
        BrokenText{"PtsAbsurdCount", true, "999999999999\n1 2 3 4\n", ErrorCode::kTruncated,
                   "line 1:", "count announces 999999999999 points"},
        BrokenText{"PtsTooMany", true, "1\n1 2 3 4\n1 2 3 4\n", ErrorCode::kFormat,
                   "line 3:", "more points than the count 1 on line 1"},
        BrokenText{"PtsFieldCount", true, "2\n1 2 3 4\n1 2 3\n", ErrorCode::kFormat,
                   "line 3:", "expected 4 fields"}),
    [](const ::testing::TestParamInfo<BrokenText>& p) { return std::string(p.param.name); });

}  // namespace
}  // namespace anascan::io
