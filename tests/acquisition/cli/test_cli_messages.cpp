// What the command line tells a user on bad input and unusable results (docs/exit-codes.md):
// errors that name the whole path and say what to do, outputs in the format asked for.
#include <gtest/gtest.h>

#include <fstream>

#include "anascan/processing/io/ply.hpp"
#include "anascan/processing/io/stanford_conf.hpp"
#include "anascan/processing/io/text_points.hpp"
#include "cli_runner.hpp"
#include "text_match.hpp"

namespace anascan {
namespace {

namespace fs = std::filesystem;
using testing_util::Cli;
using testing_util::CliRun;
using testing_util::contains;
using testing_util::run_cli;

/// A small cloud with normals: a 20 x 20 grid on a tilted plane, 1 km from the origin.
PointCloud grid_cloud() {
    PointCloud cloud;
    cloud.origin_m = {1000.0, -20.0, 3.0};
    for (int i = 0; i < 20; ++i)
        for (int j = 0; j < 20; ++j) {
            cloud.positions.emplace_back(0.01f * i, 0.01f * j, 0.002f * i);
            cloud.normals.push_back(Eigen::Vector3f(-0.2f, 0.0f, 1.0f).normalized());
        }
    return cloud;
}

void write_text(const fs::path& path, const std::string& text) { std::ofstream(path) << text; }

class MessagesCli : public Cli {
protected:
    fs::path ply() {
        const fs::path path = dir_ / "cloud.ply";
        EXPECT_TRUE(io::write_ply(path, grid_cloud()));
        return path;
    }
};

TEST_F(MessagesCli, InfoOnAnUnsupportedFormatNamesThePathAndEveryFormat) {
    for (const std::string name : {"photo.jpg", "scan.e57"}) {
        const fs::path path = dir_ / name;
        write_text(path, "not points");
        const CliRun run = run_cli("info " + path.string());
        EXPECT_EQ(run.exit_code, 1) << run.output;
        EXPECT_TRUE(contains(run.output, path.string() + ": ")) << run.output;
        for (const std::string ext : {".ply", ".ptx", ".xyz", ".txt", ".asc", ".pts"})
            EXPECT_TRUE(contains(run.output, ext)) << ext << " missing in: " << run.output;
    }
    const CliRun e57 = run_cli("info " + (dir_ / "scan.e57").string());
    EXPECT_TRUE(contains(e57.output, "E57 is not supported")) << e57.output;
}

TEST_F(MessagesCli, InfoOnAnEmptyFileSaysEmpty) {
    const fs::path path = dir_ / "empty.ply";
    write_text(path, "");
    const CliRun run = run_cli("info " + path.string());
    EXPECT_EQ(run.exit_code, 1);
    EXPECT_TRUE(contains(run.output, path.string() + ": empty file")) << run.output;
    EXPECT_FALSE(contains(run.output, "not a PLY file")) << run.output;
}

TEST_F(MessagesCli, InfoOnAConfWithMissingScansFails) {
    ply();
    io::StanfordConf conf;
    conf.entries = {{"cloud.ply", Pose::Identity()}, {"gone.ply", Pose::Identity()}};
    ASSERT_TRUE(io::write_conf(dir_ / "scans.conf", conf));
    const CliRun run = run_cli("info " + (dir_ / "scans.conf").string());
    EXPECT_EQ(run.exit_code, 1) << run.output;
    EXPECT_TRUE(contains(run.output, (dir_ / "gone.ply").string() + " is missing")) << run.output;
    EXPECT_TRUE(contains(run.output, "1 scan file(s) it names are missing")) << run.output;
    EXPECT_FALSE(contains(run.output, "cloud.ply is missing")) << run.output;
}

TEST_F(MessagesCli, ConvertWritesTheFormatTheExtensionNames) {
    const fs::path out = dir_ / "x.xyz";
    const CliRun run = run_cli("convert " + ply().string() + " " + out.string());
    ASSERT_EQ(run.exit_code, 0) << run.output;
    std::ifstream in(out);
    std::string first;
    std::getline(in, first);
    EXPECT_NE(first.rfind("ply", 0), 0u) << "PLY written under a .xyz name";
    auto back = io::read_text_points(out);
    ASSERT_TRUE(back) << back.error().message;
    const PointCloud original = grid_cloud();
    ASSERT_EQ(back->size(), original.size());
    ASSERT_TRUE(back->has_normals());
    for (std::size_t i = 0; i < original.size(); i += 37)
        EXPECT_LT((back->world_position(i) - original.world_position(i)).norm(), 2e-6);
}

TEST_F(MessagesCli, ConvertRefusesAFormatItCannotWrite) {
    const fs::path out = dir_ / "x.e57";
    const CliRun run = run_cli("convert " + ply().string() + " " + out.string());
    EXPECT_EQ(run.exit_code, 1);
    EXPECT_TRUE(contains(run.output, out.string() + ": cannot write '.e57'")) << run.output;
    EXPECT_FALSE(fs::exists(out));
}

TEST_F(MessagesCli, OutputFolderIsCheckedBeforeTheWork) {
    const fs::path scan = ply();
    const std::string scans = scan.string() + " " + scan.string();
    const fs::path out = dir_ / "no-such-folder" / "poses.conf";
    const CliRun run = run_cli("register " + scans + " --out " + out.string());
    EXPECT_EQ(run.exit_code, 1) << run.output;
    EXPECT_TRUE(contains(run.output, "--out " + out.string())) << run.output;
    EXPECT_FALSE(contains(run.output, "placed")) << "the work ran first: " << run.output;
    write_text(dir_ / "a-file", "");
    const CliRun under_file =
        run_cli("align " + scans + " --out " + (dir_ / "a-file" / "t.xf").string());
    EXPECT_EQ(under_file.exit_code, 1) << under_file.output;
    EXPECT_FALSE(contains(under_file.output, "status:")) << under_file.output;
}

TEST_F(MessagesCli, EvalMatchesByFileNameWhenPathsDiffer) {
    io::StanfordConf truth, estimated;
    for (int i = 0; i < 3; ++i) {
        const Pose T = Pose(Eigen::Translation3d(0.1 * i, 0.0, 0.0));
        truth.entries.push_back({"bun00" + std::to_string(i) + ".ply", T});
        estimated.entries.push_back({"../data/bun00" + std::to_string(i) + ".ply", T});
    }
    ASSERT_TRUE(io::write_conf(dir_ / "truth.conf", truth));
    fs::create_directories(dir_ / "reg");
    ASSERT_TRUE(io::write_conf(dir_ / "reg" / "poses.conf", estimated));
    const CliRun run = run_cli("eval " + (dir_ / "reg" / "poses.conf").string() + " --truth " +
                               (dir_ / "truth.conf").string() + " --max-rotation-deg 0.01");
    EXPECT_EQ(run.exit_code, 0) << run.output;
    EXPECT_TRUE(contains(run.output, "matched by file name")) << run.output;
    EXPECT_TRUE(contains(run.output, "placed 3 of 3")) << run.output;
}

TEST_F(MessagesCli, DemoWithAWrongBunnyPathFails) {
    const CliRun run =
        run_cli("demo --bunny " + (dir_ / "wrong").string() + " --out " + (dir_ / "demo").string());
    EXPECT_EQ(run.exit_code, 1) << run.output;
    EXPECT_TRUE(contains(run.output, (dir_ / "wrong" / "bun.conf").string() + " not found"))
        << run.output;
    EXPECT_FALSE(contains(run.output, "result:")) << run.output;
    EXPECT_FALSE(fs::exists(dir_ / "demo" / "model.ply"));
}

/// A 1 x 1 m wall at z = 0 and a 0.2 m box in front of it, its near corner at `box_x_m`.
PointCloud wall_and_box(double box_x_m) {
    PointCloud cloud;
    for (int i = 0; i < 200; ++i)
        for (int j = 0; j < 200; ++j) cloud.positions.emplace_back(0.005f * i, 0.005f * j, 0.0f);
    for (int i = 0; i <= 40; ++i)
        for (int j = 0; j <= 40; ++j) {
            const float a = 0.005f * i, b = 0.005f * j, x = float(box_x_m);
            cloud.positions.emplace_back(x + a, 0.3f + b, 0.2f);  // Front face.
            cloud.positions.emplace_back(x, 0.3f + a, b);         // Side faces.
            cloud.positions.emplace_back(x + 0.2f, 0.3f + a, b);
            cloud.positions.emplace_back(x + a, 0.3f, b);  // Bottom and top faces.
            cloud.positions.emplace_back(x + a, 0.5f, b);
        }
    return cloud;
}

// The box moved along the wall between the scans: a registration that locks onto the wall
// returns the identity, verified. That must not pass for a result.
TEST_F(MessagesCli, AlignOnAStaticBackgroundIsAPoorResult) {
    ASSERT_TRUE(io::write_ply(dir_ / "source.ply", wall_and_box(0.2)));
    ASSERT_TRUE(io::write_ply(dir_ / "target.ply", wall_and_box(0.6)));
    write_text(dir_ / "identity.xf", "1 0 0 0\n0 1 0 0\n0 0 1 0\n0 0 0 1\n");
    const std::string args = (dir_ / "source.ply").string() + " " + (dir_ / "target.ply").string() +
                             " --sensor-origin 0.5 0.5 2 ";
    const CliRun run = run_cli("align " + args + "--init " + (dir_ / "identity.xf").string());
    EXPECT_EQ(run.exit_code, 3) << run.output;
    EXPECT_TRUE(contains(run.output, "close to the identity")) << run.output;
    EXPECT_TRUE(contains(run.output, "--remove-background-plane")) << run.output;
    const CliRun empty = run_cli("align " + args + "--roi-box 5 5 5 6 6 6");
    EXPECT_EQ(empty.exit_code, 1) << empty.output;
    EXPECT_TRUE(contains(empty.output, "source.ply: no point left in the region")) << empty.output;
}

TEST_F(MessagesCli, ABadCommandLineExitsWithTheUsageCode) {
    EXPECT_EQ(run_cli("info").exit_code, 2);
    EXPECT_EQ(run_cli("no-such-command").exit_code, 2);
    EXPECT_EQ(run_cli("--help").exit_code, 0);
}

}  // namespace
}  // namespace anascan
