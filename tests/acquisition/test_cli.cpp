// Runs the `anascan` executable as a user would and checks what it prints and returns.
#include <gtest/gtest.h>
#include <sys/wait.h>
#include <unistd.h>

#include <array>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <string>

#include "cli_run.hpp"

namespace {

namespace fs = std::filesystem;

using anascan::test::CliRun;
using anascan::test::run_cli;

class Cli : public ::testing::Test {
protected:
    void SetUp() override {
        dir_ = fs::path(::testing::TempDir()) / ("cli-" + std::to_string(::getpid()));
        fs::remove_all(dir_);
        fs::create_directories(dir_);
    }
    void TearDown() override { fs::remove_all(dir_); }
    fs::path dir_;
};

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

}  // namespace
