#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <numbers>
#include <ostream>
#include <random>
#include <string>

#include "anascan/processing/io/stanford_conf.hpp"
#include "test_quaternion_util.hpp"

namespace anascan::io {
namespace {

using ::testing::HasSubstr;
namespace fs = std::filesystem;

std::span<const char> text_bytes(std::string_view text) { return {text.data(), text.size()}; }

using testing_util::hamilton_rotation;

double max_difference(const Pose& a, const Pose& b) {
    return (a.matrix() - b.matrix()).cwiseAbs().maxCoeff();
}

TEST(ConfParse, RotationIsTheTransposeOfTheQuaternions) {
    // q = 90 degrees about z: R(q) maps x to y, so p_world = R(q)^T p maps x to -y.
    const double s = std::sqrt(0.5);
    const std::string text = "bmesh a.ply 1 2 3 0 0 " + std::to_string(s) + " " +
                             std::to_string(s) + "\nbmesh b.ply 0 0 0 0 0 0 1\n";
    const auto conf = parse_conf(text_bytes(text), "two.conf");
    ASSERT_TRUE(conf.has_value()) << conf.error().message;
    ASSERT_EQ(conf->entries.size(), 2u);
    EXPECT_FALSE(conf->camera.has_value());
    const Pose& T = conf->entries[0].T_world_scan;
    EXPECT_TRUE((T * Eigen::Vector3d(1, 0, 0)).isApprox(Eigen::Vector3d(1, 1, 3), 1e-6));
    EXPECT_EQ(conf->entries[1].file, "b.ply");
    EXPECT_TRUE(conf->entries[1].T_world_scan.matrix().isIdentity(0.0));
    ASSERT_NE(conf->find("b.ply"), nullptr);
    EXPECT_EQ(conf->find("b.ply")->file, "b.ply");
    EXPECT_EQ(conf->find("c.ply"), nullptr);
}

TEST(ConfParse, CameraLineUsesTheSameConventionAndQuaternionsAreNormalised) {
    const auto conf =
        parse_conf(text_bytes("camera 0 0 -1  0 0 2 2\r\nbmesh x 0 0 0 0 0 0 5\r\n"), "cam.conf");
    ASSERT_TRUE(conf.has_value()) << conf.error().message;
    ASSERT_TRUE(conf->camera.has_value());
    const Pose expected_rotation(Eigen::Matrix3d(hamilton_rotation(0, 0, 2, 2).transpose()));
    EXPECT_LT((conf->camera->linear() - expected_rotation.linear()).cwiseAbs().maxCoeff(), 1e-15);
    EXPECT_TRUE(conf->camera->translation().isApprox(Eigen::Vector3d(0, 0, -1)));
    EXPECT_TRUE(conf->entries[0].T_world_scan.matrix().isIdentity(1e-15));
}

TEST(ConfParse, FormatRoundTripsTo1e12) {
    std::mt19937 rng(3);
    std::normal_distribution<double> normal(0.0, 1.0);
    StanfordConf conf;
    auto random_pose = [&] {
        const Eigen::Quaterniond q(normal(rng), normal(rng), normal(rng), normal(rng));
        return make_pose(q, Eigen::Vector3d(normal(rng), normal(rng), normal(rng)));
    };
    conf.camera = random_pose();
    for (int i = 0; i < 20; ++i)
        conf.entries.push_back({"scan" + std::to_string(i), random_pose()});
    const std::string text = format_conf(conf);
    const auto back = parse_conf(text_bytes(text), "rt.conf");
    ASSERT_TRUE(back.has_value()) << back.error().message;
    ASSERT_EQ(back->entries.size(), conf.entries.size());
    EXPECT_LT(max_difference(*back->camera, *conf.camera), 1e-12);
    for (std::size_t i = 0; i < conf.entries.size(); ++i) {
        EXPECT_EQ(back->entries[i].file, conf.entries[i].file);
        EXPECT_LT(max_difference(back->entries[i].T_world_scan, conf.entries[i].T_world_scan),
                  1e-12);
    }
}

TEST(ConfFile, WriteThenReadAndRefuseUnwritableNames) {
    const fs::path dir = fs::path(ANASCAN_BINARY_DIR) / "test-tmp" / "conf";
    fs::create_directories(dir);
    StanfordConf conf;
    conf.entries.push_back({"a.ply", make_pose(Eigen::Quaterniond(1, 2, 3, 4), {1, 2, 3})});
    ASSERT_TRUE(write_conf(dir / "scans.conf", conf).has_value());
    const auto back = read_conf(dir / "scans.conf");
    ASSERT_TRUE(back.has_value()) << back.error().message;
    EXPECT_LT(max_difference(back->entries[0].T_world_scan, conf.entries[0].T_world_scan), 1e-12);
    conf.entries.push_back({"two words.ply", Pose::Identity()});
    const auto refused = write_conf(dir / "bad.conf", conf);
    ASSERT_FALSE(refused.has_value());
    EXPECT_EQ(refused.error().code, ErrorCode::kInvalidArgument);
    EXPECT_THAT(refused.error().message, HasSubstr("two words.ply"));
}

struct BrokenConf {
    const char* name;
    const char* text;
    ErrorCode code;
    const char* line;
    const char* what;
};

// Shows the case name instead of the bytes in test output.
void PrintTo(const BrokenConf& broken, std::ostream* os) { *os << broken.name; }

class ConfErrors : public ::testing::TestWithParam<BrokenConf> {};

TEST_P(ConfErrors, NameSourceLineAndProblem) {
    const BrokenConf& broken = GetParam();
    const auto conf = parse_conf(text_bytes(broken.text), "scans.conf");
    ASSERT_FALSE(conf.has_value()) << broken.name;
    EXPECT_EQ(conf.error().code, broken.code) << conf.error().message;
    EXPECT_THAT(conf.error().message, HasSubstr(std::string("scans.conf: ") + broken.line));
    EXPECT_THAT(conf.error().message, HasSubstr(broken.what));
}

constexpr const char* kGood =
    "camera 0 0 0 0 0 0 1\nbmesh a 0 0 0 0 0 0 1\nbmesh b 0 0 0 0 0 0 1\n";

INSTANTIATE_TEST_SUITE_P(
    Kinds, ConfErrors,
    ::testing::Values(
        BrokenConf{"Empty", "", ErrorCode::kEmpty, "line 1:", "without any 'bmesh"},
        BrokenConf{"CameraOnly", "camera 0 0 0 0 0 0 1\n", ErrorCode::kEmpty,
                   "line 1:", "without any"},
        BrokenConf{"FieldCount", "camera 0 0 0 0 0 0 1\nbmesh a 0 0 0 0 0 0 1\n\nbmesh c 1 2 3 4\n",
                   ErrorCode::kFormat,
                   "line 4:", "expected 'bmesh FILE tx ty tz qx qy qz qw', found 6 fields"},
        BrokenConf{"CameraFieldCount", "camera 0 0 0 0 0 1\n", ErrorCode::kFormat,
                   "line 1:", "expected 'camera tx ty tz qx qy qz qw', found 7 fields"},
        BrokenConf{"UnknownKeyword", "bmesh a 0 0 0 0 0 0 1\nmesh b 0 0 0 0 0 0 1\n",
                   ErrorCode::kFormat, "line 2:", "unknown keyword 'mesh'"},
        BrokenConf{"NotANumber", "bmesh a 0 0 0 0 0 x 1\n", ErrorCode::kFormat,
                   "line 1:", "field 8 'x' is not a number"},
        BrokenConf{"NaNTranslation", "bmesh a 0 NaN 0 0 0 0 1\n", ErrorCode::kFormat,
                   "line 1:", "not finite"},
        BrokenConf{"InfQuaternion", "bmesh a 0 0 0 0 0 0 inf\n", ErrorCode::kFormat,
                   "line 1:", "not finite"},
        BrokenConf{"ZeroQuaternion", "bmesh a 0 0 0 0 0 0 1e-9\n", ErrorCode::kFormat,
                   "line 1:", "near-zero norm"},
        BrokenConf{"Duplicate", "bmesh a 0 0 0 0 0 0 1\n# c\nbmesh a 1 0 0 0 0 0 1\n",
                   ErrorCode::kFormat, "line 3:", "duplicate file 'a' (first on line 1)"},
        BrokenConf{"SecondCamera", "camera 0 0 0 0 0 0 1\ncamera 0 0 0 0 0 0 1\n",
                   ErrorCode::kFormat, "line 2:", "second 'camera'"}),
    [](const ::testing::TestParamInfo<BrokenConf>& p) { return std::string(p.param.name); });

TEST(ConfParse, GoodSampleParses) { EXPECT_TRUE(parse_conf(text_bytes(kGood), "g.conf")); }

}  // namespace
}  // namespace anascan::io
