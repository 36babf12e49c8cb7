#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <cstdio>
#include <ostream>
#include <string>
#include <vector>

#include "anascan/processing/io/ptx.hpp"

namespace anascan::io {
namespace {

using ::testing::HasSubstr;

std::span<const char> text_bytes(std::string_view text) { return {text.data(), text.size()}; }

std::string numbers(std::initializer_list<double> values) {
    std::string out;
    for (const double v : values) {
        char buffer[32];
        std::snprintf(buffer, sizeof buffer, "%.17g", v);
        out += (out.empty() ? "" : " ") + std::string(buffer);
    }
    return out + "\n";
}

// A PTX header as Cyclone writes it: M = T_world_scan^T (translation in the last row).
std::string ptx_header(int cols, int rows, const Pose& T, const Eigen::Vector3d& position) {
    const Eigen::Matrix4d M = T.matrix().transpose();
    std::string out = std::to_string(cols) + "\n" + std::to_string(rows) + "\n";
    out += numbers({position.x(), position.y(), position.z()});
    for (int i = 0; i < 3; ++i) out += numbers({M(i, 0), M(i, 1), M(i, 2)});
    for (int i = 0; i < 4; ++i) out += numbers({M(i, 0), M(i, 1), M(i, 2), M(i, 3)});
    return out;
}

Pose station_pose() {
    return make_pose(
        Eigen::Quaterniond(Eigen::AngleAxisd(0.3, Eigen::Vector3d(1, 2, 3).normalized())),
        Eigen::Vector3d(10, 20, 5));
}

// 2 columns x 3 rows, column-major; point k is (k+1, 0, 0.5) with intensity k/10, except
// k = 4 (row 1, column 1), a missing return.
std::string two_by_three(const Pose& T, const Eigen::Vector3d& position) {
    std::string text = ptx_header(2, 3, T, position);
    for (int k = 0; k < 6; ++k) {
        text += k == 4 ? "0 0 0 0.5\r\n" : numbers({k + 1.0, 0.0, 0.5, k / 10.0});
    }
    return text;
}

TEST(PtxParse, GridPoseAndMissingReturns) {
    const Pose T = station_pose();
    const auto scans = parse_ptx(text_bytes(two_by_three(T, T.translation())), "dir/station.ptx");
    ASSERT_TRUE(scans.has_value()) << scans.error().message;
    ASSERT_EQ(scans->size(), 1u);
    const PtxScan& s = scans->front();
    EXPECT_EQ(s.grid.rows, 3);
    EXPECT_EQ(s.grid.cols, 2);
    const std::vector<std::int32_t> row_major = {0, 3, 1, RangeGrid::kNoSample, 2, 4};
    EXPECT_EQ(s.grid.point_index, row_major);
    ASSERT_EQ(s.scan.cloud.size(), 5u);
    EXPECT_TRUE(s.scan.cloud.attributes_consistent());
    EXPECT_EQ(s.scan.cloud.positions[4], Eigen::Vector3f(6, 0, 0.5f));
    EXPECT_FLOAT_EQ(s.scan.cloud.intensity[4], 0.5f);
    EXPECT_FALSE(s.scan.cloud.has_colors());
    EXPECT_EQ(s.scan.meta.id, "station#0");
    EXPECT_EQ(s.scan.meta.device_kind, DeviceKind::kTimeOfFlight);
    ASSERT_TRUE(s.scan.meta.T_world_scan.has_value());
    EXPECT_LT((s.scan.meta.T_world_scan->matrix() - T.matrix()).cwiseAbs().maxCoeff(), 1e-12);
    ASSERT_TRUE(s.scan.meta.sensor_origin_scan_m.has_value());
    EXPECT_LT(s.scan.meta.sensor_origin_scan_m->norm(), 1e-12);
}

TEST(PtxParse, SeveralScansColoursAndScannerPosition) {
    std::string text = two_by_three(Pose::Identity(), Eigen::Vector3d::Zero());
    text += ptx_header(1, 2, Pose::Identity(), Eigen::Vector3d(1, 0, 0));
    text += "1 2 3 0.25 10 20 30\n4 5 6 0.75 40 50 60\n";
    const auto scans = parse_ptx(text_bytes(text), "site.ptx");
    ASSERT_TRUE(scans.has_value()) << scans.error().message;
    ASSERT_EQ(scans->size(), 2u);
    EXPECT_TRUE((*scans)[0].scan.meta.sensor_origin_scan_m->isZero(0.0));
    const Scan& second = (*scans)[1].scan;
    EXPECT_EQ(second.meta.id, "site#1");
    EXPECT_EQ(*second.meta.sensor_origin_scan_m, Eigen::Vector3d(1, 0, 0));
    ASSERT_EQ(second.cloud.colors.size(), 2u);
    EXPECT_EQ(second.cloud.colors[1], (Rgb8{40, 50, 60}));
    EXPECT_EQ((*scans)[1].grid.point_index, (std::vector<std::int32_t>{0, 1}));
}

TEST(PtxParse, AllMissingScanIsAnEmptyGrid) {
    const std::string text =
        ptx_header(1, 2, Pose::Identity(), Eigen::Vector3d::Zero()) + "0 0 0 0.5\n0 0 0 0.5\n";
    const auto scans = parse_ptx(text_bytes(text), "s.ptx");
    ASSERT_TRUE(scans.has_value()) << scans.error().message;
    EXPECT_TRUE(scans->front().scan.cloud.empty());
    EXPECT_EQ(scans->front().grid.point_index, (std::vector<std::int32_t>(2, -1)));
}

struct BrokenPtx {
    const char* name;
    std::string text;
    ErrorCode code;
    const char* line;
    const char* what;
};

// Shows the case name instead of the bytes in test output.
void PrintTo(const BrokenPtx& broken, std::ostream* os) { *os << broken.name; }

class PtxErrors : public ::testing::TestWithParam<BrokenPtx> {};

TEST_P(PtxErrors, NameSourceLineAndProblem) {
    const BrokenPtx& broken = GetParam();
    const auto scans = parse_ptx(text_bytes(broken.text), "site.ptx");
    ASSERT_FALSE(scans.has_value()) << broken.name;
    EXPECT_EQ(scans.error().code, broken.code) << scans.error().message;
    EXPECT_THAT(scans.error().message, HasSubstr(std::string("site.ptx: ") + broken.line));
    EXPECT_THAT(scans.error().message, HasSubstr(broken.what));
}

const std::string kIdentity = "1 0 0\n0 1 0\n0 0 1\n1 0 0 0\n0 1 0 0\n0 0 1 0\n0 0 0 1\n";
const std::string kHeader2x2 = "2\n2\n0 0 0\n" + kIdentity;
const std::string kPoint = "0.100 0.200 0.300 0.5\n";

INSTANTIATE_TEST_SUITE_P(
    Kinds, PtxErrors,
    ::testing::Values(
        BrokenPtx{"Empty", "\n", ErrorCode::kEmpty, "line 1:", "no scan"},
        BrokenPtx{"TruncatedHeader", "1\n1\n0 0 0\n1 0 0\n", ErrorCode::kTruncated,
                  "line 4:", "file ends in the header of scan 0: expected the scanner y axis"},
        BrokenPtx{"TruncatedPoints", kHeader2x2 + kPoint + kPoint + kPoint, ErrorCode::kTruncated,
                  "line 13:", "file ends after 3 of 4 points of scan 0"},
        BrokenPtx{"SecondScanTruncated", kHeader2x2 + kPoint + kPoint + kPoint + kPoint + "1\n",
                  ErrorCode::kTruncated, "line 15:", "scan 1"},
        BrokenPtx{"AbsurdColumns", "999999999\n5\n0 0 0\n" + kIdentity + kPoint,
                  ErrorCode::kTruncated, "line 2:", "announces 999999999 x 5 points"},
        BrokenPtx{"ZeroRows", "3\n0\n", ErrorCode::kFormat, "line 2:", "the row count is 0"},
        BrokenPtx{"NegativeColumns", "-3\n2\n", ErrorCode::kFormat,
                  "line 1:", "expected a whole number, found '-3'"},
        BrokenPtx{"PositionFields", "1\n1\n0 0\n" + kIdentity + kPoint, ErrorCode::kFormat,
                  "line 3:", "expected the scanner position (3 numbers), found 2 fields"},
        BrokenPtx{
            "NaNInTransform",
            "1\n1\n0 0 0\n1 0 0\n0 1 0\n0 0 1\n1 0 0 0\n0 1 0 0\n0 0 1 0\nnan 0 0 1\n" + kPoint,
            ErrorCode::kFormat, "line 10:", "field 1 'nan' is not finite"},
        BrokenPtx{
            "LastColumn",
            "1\n1\n0 0 0\n1 0 0\n0 1 0\n0 0 1\n1 0 0 0\n0 1 0 0.5\n0 0 1 0\n0 0 0 1\n" + kPoint,
            ErrorCode::kFormat, "line 8:", "last column must be 0 0 0 1"},
        BrokenPtx{"NotARotation",
                  "1\n1\n0 0 0\n1 0 0\n0 1 0\n0 0 1\n1 0 0 0\n0 3 0 0\n0 0 1 0\n0 0 0 1\n" + kPoint,
                  ErrorCode::kFormat, "line 7:", "not a rotation"},
        BrokenPtx{"PointNotANumber", kHeader2x2 + kPoint + "0.1 x 0.3 0.5\n" + kPoint + kPoint,
                  ErrorCode::kFormat, "line 12:", "field 2 'x' is not a number"},
        BrokenPtx{"PointFieldCount", kHeader2x2 + kPoint + "0.1 0.2 0.3 0.5 7\n" + kPoint + kPoint,
                  ErrorCode::kFormat, "line 12:", "(4 fields), found 5"},
        BrokenPtx{"PointColour", kHeader2x2 + "0.1 0.2 0.3 0.5 1 2 300\n" + kPoint,
                  ErrorCode::kFormat, "line 11:", "field 7 '300' is not a colour"}),
    [](const ::testing::TestParamInfo<BrokenPtx>& p) { return std::string(p.param.name); });

}  // namespace
}  // namespace anascan::io
