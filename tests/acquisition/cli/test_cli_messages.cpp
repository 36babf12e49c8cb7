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
    for (const std::string name : {"photo.jpg", "scan.las"}) {
        const fs::path path = dir_ / name;
        write_text(path, "not points");
        const CliRun run = run_cli("info " + path.string());
        EXPECT_EQ(run.exit_code, 1) << run.output;
        EXPECT_TRUE(contains(run.output, path.string() + ": ")) << run.output;
        for (const std::string ext : {".ply", ".ptx", ".e57", ".xyz", ".txt", ".asc", ".pts"})
            EXPECT_TRUE(contains(run.output, ext)) << ext << " missing in: " << run.output;
    }
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
        // 6 decimals in the file; the XYZ reader parses floats, 6e-5 m apart at 1 km.
        EXPECT_LT((back->world_position(i) - original.world_position(i)).norm(), 1e-4);
}

TEST_F(MessagesCli, ConvertRefusesAFormatItCannotWrite) {
    const fs::path out = dir_ / "x.las";
    const CliRun run = run_cli("convert " + ply().string() + " " + out.string());
    EXPECT_EQ(run.exit_code, 1);
    EXPECT_TRUE(contains(run.output, out.string() + ": cannot write '.las'")) << run.output;
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

/// The corner of a room (three 0.8 m walls) and a 0.3 m box standing off the walls, its
/// near corner at `box_x_m`: the static background fixes all six degrees of freedom.
PointCloud wall_and_box(double box_x_m) {
    PointCloud cloud;
    for (int i = 0; i < 80; ++i)
        for (int j = 0; j < 80; ++j) {
            const float a = 0.01f * i, b = 0.01f * j;
            cloud.positions.emplace_back(a, b, 0.0f);
            cloud.positions.emplace_back(a, 0.0f, b);
            cloud.positions.emplace_back(0.0f, a, b);
        }
    for (int i = 0; i <= 60; ++i)
        for (int j = 0; j <= 60; ++j) {
            const float a = 0.005f * i, b = 0.005f * j, x = float(box_x_m);
            cloud.positions.emplace_back(x + a, 0.2f + b, 0.4f);  // Front face.
            cloud.positions.emplace_back(x, 0.2f + a, 0.1f + b);  // Side faces.
            cloud.positions.emplace_back(x + 0.3f, 0.2f + a, 0.1f + b);
            cloud.positions.emplace_back(x + a, 0.2f, 0.1f + b);  // Bottom and top faces.
            cloud.positions.emplace_back(x + a, 0.5f, 0.1f + b);
        }
    return cloud;
}

// The box moved along the wall between the scans: a registration that locks onto the wall
// returns the identity, verified. That must not pass for a result.
TEST_F(MessagesCli, AlignOnAStaticBackgroundIsAPoorResult) {
    ASSERT_TRUE(io::write_ply(dir_ / "source.ply", wall_and_box(0.05)));
    ASSERT_TRUE(io::write_ply(dir_ / "target.ply", wall_and_box(0.45)));
    write_text(dir_ / "identity.xf", "1 0 0 0\n0 1 0 0\n0 0 1 0\n0 0 0 1\n");
    const std::string args = (dir_ / "source.ply").string() + " " + (dir_ / "target.ply").string() +
                             " --sensor-origin 1 1 1.5 ";
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
