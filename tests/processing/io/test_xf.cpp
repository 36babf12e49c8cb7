#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <ostream>
#include <random>
#include <string>

#include "anascan/processing/io/xf.hpp"

namespace anascan::io {
namespace {

using ::testing::HasSubstr;

std::span<const char> text_bytes(std::string_view text) { return {text.data(), text.size()}; }

Pose random_pose(std::mt19937& rng) {
    std::normal_distribution<double> normal(0.0, 1.0);
    const Eigen::Quaterniond q(normal(rng), normal(rng), normal(rng), normal(rng));
    return make_pose(q, Eigen::Vector3d(normal(rng), normal(rng), normal(rng)) * 10.0);
}

TEST(XfParse, IdentityMatrix) {
    const auto T = parse_xf(text_bytes("1 0 0 0\n0 1 0 0\n0 0 1 0\n0 0 0 1\n"), "id.xf");
    ASSERT_TRUE(T.has_value()) << T.error().message;
    EXPECT_TRUE(T->matrix().isIdentity(0.0));
}

TEST(XfParse, RowMajorWithTranslationInLastColumn) {
    // 90 degrees about z, then a shift: (1,0,0) -> (0,1,0) + t.
    const std::string text = "0 -1 0 1.5\r\n1e0 0 0 -2\r\n  # comment\n0 0 +1 0.25\n0 0 0 1\n";
    const auto T = parse_xf(text_bytes(text), "rz.xf");
    ASSERT_TRUE(T.has_value()) << T.error().message;
    EXPECT_TRUE((*T * Eigen::Vector3d(1, 0, 0)).isApprox(Eigen::Vector3d(1.5, -1.0, 0.25), 1e-15));
    EXPECT_TRUE(T->translation().isApprox(Eigen::Vector3d(1.5, -2.0, 0.25)));
}

TEST(XfParse, FormatRoundTripsToMachinePrecision) {
    std::mt19937 rng(7);
    for (int i = 0; i < 50; ++i) {
        const Pose T = random_pose(rng);
        const std::string text = format_xf(T);
        const auto back = parse_xf(text_bytes(text), "rt.xf");
        ASSERT_TRUE(back.has_value()) << back.error().message;
        EXPECT_LT((back->matrix() - T.matrix()).cwiseAbs().maxCoeff(), 1e-12) << text;
    }
}

TEST(XfParse, SlightlyNonOrthonormalRotationIsRepaired) {
    const auto T = parse_xf(text_bytes("1.00001 0 0 0\n0 1 0.00002 0\n0 0 1 0\n0 0 0 1\n"), "a.xf");
    ASSERT_TRUE(T.has_value()) << T.error().message;
    const Eigen::Matrix3d R = T->linear();
    EXPECT_LT((R.transpose() * R - Eigen::Matrix3d::Identity()).cwiseAbs().maxCoeff(), 1e-14);
}

TEST(XfFile, WriteThenRead) {
    const auto dir = std::filesystem::path(ANASCAN_BINARY_DIR) / "test-tmp" / "xf";
    std::filesystem::create_directories(dir);
    std::mt19937 rng(11);
    const Pose T = random_pose(rng);
    ASSERT_TRUE(write_xf(dir / "pose.xf", T).has_value());
    const auto back = read_xf(dir / "pose.xf");
    ASSERT_TRUE(back.has_value()) << back.error().message;
    EXPECT_LT((back->matrix() - T.matrix()).cwiseAbs().maxCoeff(), 1e-12);
    const auto missing = read_xf(dir / "missing.xf");
    ASSERT_FALSE(missing.has_value());
    EXPECT_EQ(missing.error().code, ErrorCode::kIo);
    EXPECT_THAT(missing.error().message, HasSubstr("missing.xf"));
}

struct BrokenXf {
    const char* name;
    const char* text;
    ErrorCode code;
    const char* line;
    const char* what;
};

// Shows the case name instead of the bytes in test output.
void PrintTo(const BrokenXf& broken, std::ostream* os) { *os << broken.name; }

class XfErrors : public ::testing::TestWithParam<BrokenXf> {};

TEST_P(XfErrors, NameSourceLineAndProblem) {
    const BrokenXf& broken = GetParam();
    const auto T = parse_xf(text_bytes(broken.text), "pose.xf");
    ASSERT_FALSE(T.has_value()) << broken.name;
    EXPECT_EQ(T.error().code, broken.code) << T.error().message;
    EXPECT_THAT(T.error().message, HasSubstr(std::string("pose.xf: ") + broken.line));
    EXPECT_THAT(T.error().message, HasSubstr(broken.what));
}

INSTANTIATE_TEST_SUITE_P(
    Kinds, XfErrors,
    ::testing::Values(BrokenXf{"Empty", "", ErrorCode::kTruncated, "line 1:", "found 0 lines"},
                      BrokenXf{"ThreeLines", "1 0 0 0\n0 1 0 0\n0 0 1 0\n", ErrorCode::kTruncated,
                               "line 3:", "found 3 lines"},
                      BrokenXf{"FiveNumbers", "1 0 0 0\n0 1 0 0 7\n0 0 1 0\n0 0 0 1\n",
                               ErrorCode::kFormat, "line 2:", "found 5 fields"},
                      BrokenXf{"NotANumber", "1 0 0 0\n0 1 0 0\n0 0 one 0\n0 0 0 1\n",
                               ErrorCode::kFormat, "line 3:", "field 3 'one' is not a number"},
                      BrokenXf{"NaN", "1 0 0 nan\n0 1 0 0\n0 0 1 0\n0 0 0 1\n", ErrorCode::kFormat,
                               "line 1:", "not finite"},
                      BrokenXf{"Infinity", "1 0 0 0\n0 1 0 -inf\n0 0 1 0\n0 0 0 1\n",
                               ErrorCode::kFormat, "line 2:", "not finite"},
                      BrokenXf{"BottomRow", "1 0 0 0\n0 1 0 0\n0 0 1 0\n0 0 1 1\n",
                               ErrorCode::kFormat, "line 4:", "0 0 0 1"},
                      BrokenXf{"Scaled", "\n2 0 0 0\n0 2 0 0\n0 0 2 0\n0 0 0 1\n",
                               ErrorCode::kFormat, "line 2:", "not a rotation"},
                      BrokenXf{"Reflection", "-1 0 0 0\n0 1 0 0\n0 0 1 0\n0 0 0 1\n",
                               ErrorCode::kFormat, "line 1:", "not a rotation"},
                      BrokenXf{"TrailingLine", "1 0 0 0\n0 1 0 0\n0 0 1 0\n0 0 0 1\n1 2 3 4\n",
                               ErrorCode::kFormat, "line 5:", "after the 4x4 matrix"}),
    [](const ::testing::TestParamInfo<BrokenXf>& p) { return std::string(p.param.name); });

}  // namespace
}  // namespace anascan::io
