// `anascan align` and `anascan register` run as a user runs them, on synthetic bumpy scans
// with known poses (no shared data needed), and on bad files: each gets its own message.
#include <gtest/gtest.h>

#include <fstream>
#include <limits>
#include <nlohmann/json.hpp>
#include <random>
#include <string>

#include "../processing/test_bumpy_surface.hpp"
#include "anascan/processing/evaluation/pose_sampling.hpp"
#include "anascan/processing/io/ply.hpp"
#include "anascan/processing/io/xf.hpp"
#include "cli_runner.hpp"

namespace anascan {
namespace {

namespace fs = std::filesystem;
using testing_util::Cli;
using testing_util::CliRun;
using testing_util::run_cli;

class CliRegistration : public Cli {
protected:
    /// Two overlapping windows of one bumpy surface; b is written in a random frame.
    void SetUp() override {
        Cli::SetUp();
        const std::vector<testing_util::Bump> bumps = testing_util::random_bumps(7, 14);
        std::mt19937 rng(5);
        T_b_object_ = sample_random_pose(rng, 0.3);
        write(dir_ / "a.ply", testing_util::bumpy_surface(bumps, -0.1, 0.02, 0.001, 0.0));
        write(dir_ / "b.ply",
              transformed(testing_util::bumpy_surface(bumps, -0.06, 0.06, 0.001, 0.0003),
                          T_b_object_));
    }
    static void write(const fs::path& path, const PointCloud& cloud) {
        ASSERT_TRUE(io::write_ply(path, cloud).has_value()) << path;
    }
    std::string path(const char* name) const { return (dir_ / name).string(); }
    Pose T_b_object_ = Pose::Identity();
};

TEST_F(CliRegistration, AlignWritesTheTransformAndStatsWithUnits) {
    const CliRun run = run_cli("align " + path("b.ply") + " " + path("a.ply") + " --out " +
                               path("T.xf") + " --stats " + path("S.json"));
    ASSERT_EQ(run.exit_code, 0) << run.output;
    EXPECT_NE(run.output.find(" mm"), std::string::npos) << run.output;
    auto T = io::read_xf(dir_ / "T.xf");
    ASSERT_TRUE(T.has_value()) << T.error().message;
    const PoseDifference error = pose_difference(*T, T_b_object_.inverse());
    EXPECT_LT(error.rotation_deg, 0.5);
    EXPECT_LT(error.translation_m, 0.002);  // At the frame origin, up to 0.3 m from the data.
    const nlohmann::json stats = nlohmann::json::parse(std::ifstream(dir_ / "S.json"));
    for (const char* stage : {"load", "normals", "global_matching", "fine"}) {
        EXPECT_TRUE(stats["stages"].contains(stage)) << stage;
    }
    for (const char* figure : {"iterations", "time_s", "rms_m", "overlap"}) {
        EXPECT_TRUE(stats["fine"].contains(figure)) << figure;
    }
    EXPECT_GT(stats["fine"]["overlap"].get<double>(), 0.25);
}

/// The figure of the "rms: X mm (agreement..." line, or -1.
double reported_rms_mm(const std::string& output) {
    const std::size_t at = output.find("\nrms: ");
    if (at == std::string::npos || output.find(" mm (agreement", at) == std::string::npos)
        return -1.0;
    return std::stod(output.substr(at + 6));
}

// Global + fine, then fine only from that result: nearly the same pose, so the same RMS
// (one definition, named, whatever gates each run used).
TEST_F(CliRegistration, AlignReportsOneRmsDefinition) {
    const CliRun global =
        run_cli("align " + path("b.ply") + " " + path("a.ply") + " --out " + path("T.xf"));
    ASSERT_EQ(global.exit_code, 0) << global.output;
    const CliRun again =
        run_cli("align " + path("b.ply") + " " + path("a.ply") + " --init " + path("T.xf"));
    ASSERT_EQ(again.exit_code, 0) << again.output;
    const double first = reported_rms_mm(global.output), second = reported_rms_mm(again.output);
    ASSERT_GT(first, 0.0) << global.output;
    ASSERT_GT(second, 0.0) << again.output;
    EXPECT_NEAR(second, first, 0.03 * first) << global.output << again.output;
}

TEST_F(CliRegistration, AlignOfUnrelatedScansFailsVerification) {
    PointCloud line;
    for (int i = 0; i < 2000; ++i) line.positions.push_back({0.0001f * i, 0.0f, 0.0f});
    write(dir_ / "line.ply", line);
    const CliRun run = run_cli("align " + path("line.ply") + " " + path("a.ply"));
    EXPECT_EQ(run.exit_code, 1) << run.output;
    EXPECT_NE(run.output.find("anascan: error: "), std::string::npos) << run.output;
}

TEST_F(CliRegistration, RegisterPlacesGoodScansAndNamesEachBadOne) {
    std::ofstream(dir_ / "truncated.ply")
        << "ply\nformat binary_little_endian 1.0\nelement vertex 1000\n"
           "property float x\nproperty float y\nproperty float z\nend_header\n";
    PointCloud nan_cloud;
    nan_cloud.positions.assign(300,
                               Eigen::Vector3f::Constant(std::numeric_limits<float>::quiet_NaN()));
    write(dir_ / "nan.ply", nan_cloud);
    write(dir_ / "empty.ply", PointCloud{});
    fs::copy_file(dir_ / "a.ply", dir_ / "a_again.ply");

    const CliRun run =
        run_cli("register " + path("a.ply") + " " + path("truncated.ply") + " " + path("b.ply") +
                " " + path("nan.ply") + " " + path("empty.ply") + " " + path("a_again.ply") +
                " --out " + path("poses.conf") + " --stats " + path("stats.json"));
    ASSERT_EQ(run.exit_code, 0) << run.output;
    const auto says = [&](const std::string& text) {
        EXPECT_NE(run.output.find(text), std::string::npos) << text << "\n" << run.output;
    };
    says("not placed: " + path("truncated.ply") +
         ": could not be loaded: " + path("truncated.ply"));
    says("not placed: " + path("nan.ply") + ": all 300 points are non-finite");
    says("not placed: " + path("empty.ply") + ": empty scan");
    says(path("a_again.ply") + ": the same points as " + path("a.ply"));
    says("placed 3 of 6 scans");
    std::string text, line;
    for (std::ifstream conf(dir_ / "poses.conf"); std::getline(conf, line);) text += line + "\n";
    EXPECT_NE(text.find("bmesh b.ply"), std::string::npos) << text;
    EXPECT_EQ(text.find("nan.ply"), std::string::npos) << text;
    const nlohmann::json stats = nlohmann::json::parse(std::ifstream(dir_ / "stats.json"));
    for (const char* stage : {"prepare", "features", "matching", "pairwise", "fine", "multiview"}) {
        EXPECT_TRUE(stats["stages"].contains(stage)) << stage;
    }
    for (const char* figure : {"iterations", "time_s", "rms_m", "overlap"}) {
        EXPECT_TRUE(stats["fine"].contains(figure)) << figure;
    }
}

}  // namespace
}  // namespace anascan
