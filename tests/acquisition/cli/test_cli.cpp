// Runs the `anascan` executable as a user would and checks what it prints and returns.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <string>

#include "anascan/processing/io/ply.hpp"
#include "cli_runner.hpp"

namespace {

namespace fs = std::filesystem;
using anascan::testing_util::Cli;
using anascan::testing_util::CliRun;
using anascan::testing_util::run_cli;

TEST_F(Cli, HelpListsTheCommands) {
    const CliRun run = run_cli("--help");
    EXPECT_EQ(run.exit_code, 0);
    for (const char* command : {"info", "convert", "assemble", "demo"}) {
        EXPECT_NE(run.output.find(command), std::string::npos) << command;
    }
}

TEST_F(Cli, SyntheticDemoRunsEndToEnd) {
    const CliRun run = run_cli("demo --out " + (dir_ / "demo").string());
    ASSERT_EQ(run.exit_code, 0) << run.output;
    EXPECT_TRUE(fs::exists(dir_ / "demo/model.ply"));
    EXPECT_TRUE(fs::exists(dir_ / "demo/report.json"));
    EXPECT_NE(run.output.find(" mm"), std::string::npos) << "figures name their unit";
    const CliRun info = run_cli("info " + (dir_ / "demo/model.ply").string());
    EXPECT_EQ(info.exit_code, 0) << info.output;
    EXPECT_NE(info.output.find("points:"), std::string::npos) << info.output;
}

TEST_F(Cli, ACorruptFileGivesAClearErrorNotACrash) {
    const fs::path bad = dir_ / "broken.ply";
    std::ofstream(bad) << "ply\nformat binary_little_endian 1.0\nelement vertex 1000\n"
                          "property float x\nproperty float y\nproperty float z\nend_header\n";
    const CliRun run = run_cli("info " + bad.string());
    EXPECT_EQ(run.exit_code, 1);
    EXPECT_NE(run.output.find("anascan: error: "), std::string::npos) << run.output;
    EXPECT_NE(run.output.find("broken.ply"), std::string::npos) << run.output;
}

TEST_F(Cli, ConvertWritesAsciiThatReadsBack) {
    const fs::path xyz = dir_ / "points.xyz";
    std::ofstream(xyz) << "0 0 0\n1 0 0\n0 1 0.5\n";
    const CliRun run =
        run_cli("convert " + xyz.string() + " " + (dir_ / "p.ply").string() + " --format ascii");
    ASSERT_EQ(run.exit_code, 0) << run.output;
    const CliRun info = run_cli("info " + (dir_ / "p.ply").string());
    EXPECT_NE(info.output.find("points: 3"), std::string::npos) << info.output;
    EXPECT_NE(info.output.find("ascii"), std::string::npos) << info.output;
}

TEST_F(Cli, UnknownOptionIsAUsageError) {
    const CliRun run = run_cli("info --no-such-option x.ply");
    EXPECT_NE(run.exit_code, 0);
    EXPECT_NE(run.exit_code, 1);  // usage errors are not runtime failures
}

TEST_F(Cli, SimListsScenesAndExportsTheGroundTruthMesh) {
    const CliRun list = run_cli("sim list-scenes");
    ASSERT_EQ(list.exit_code, 0) << list.output;
    EXPECT_NE(list.output.find("octagon-block-turned"), std::string::npos) << list.output;
    const fs::path mesh = dir_ / "small.ply";
    const CliRun run =
        run_cli("sim export-scene small-block --stone-only --step-mm 8 --out " + mesh.string());
    ASSERT_EQ(run.exit_code, 0) << run.output;
    const auto ply = anascan::io::read_ply(mesh);
    ASSERT_TRUE(ply.has_value()) << ply.error().message;
    EXPECT_GT(ply->triangles.size(), 1000u);
    const anascan::Bounds b = anascan::local_bounds(ply->cloud);
    EXPECT_NEAR(b.min.z() + ply->cloud.origin_m.z(), 0.0, 0.002);  // Lies on the ground.
    EXPECT_NEAR(b.max.z() + ply->cloud.origin_m.z(), 0.35, 0.002);
}

TEST_F(Cli, SimUnknownSceneIsAClearError) {
    const CliRun run = run_cli("sim export-scene pyramid --out " + (dir_ / "x.ply").string());
    EXPECT_EQ(run.exit_code, 1);
    EXPECT_NE(run.output.find("unknown scene 'pyramid'"), std::string::npos) << run.output;
    EXPECT_NE(run.output.find("octagon-block"), std::string::npos) << run.output;
}

TEST_F(Cli, SimScannersWriteScansImagesAndTruth) {
    const fs::path scan = dir_ / "tof.ply";
    const CliRun tof =
        run_cli("sim tof-scan small-block --step-mm 8 --step-deg 1 --out " + scan.string());
    ASSERT_EQ(tof.exit_code, 0) << tof.output;
    EXPECT_TRUE(fs::exists(dir_ / "tof.conf"));
    EXPECT_NE(tof.output.find("range error RMS"), std::string::npos) << tof.output;
    const fs::path sl = dir_ / "sl";
    const CliRun capture = run_cli(
        "sim sl-capture small-block --step-mm 8 --camera-width 64 "
        "--camera-height 48 --out " +
        sl.string());
    ASSERT_EQ(capture.exit_code, 0) << capture.output;
    EXPECT_TRUE(fs::exists(sl / "calibration.yml"));
    EXPECT_TRUE(fs::exists(sl / "pattern_cam1_im01.png"));
    EXPECT_TRUE(fs::exists(sl / "pattern_cam2_im44.png"));  // Gray code + white + black.
    EXPECT_TRUE(fs::exists(sl / "stone_in_cam1.ply"));
}

}  // namespace
