// `anascan sim sl-capture` written to disk, then `anascan sl decode` on it, as a user runs
// them: the simulated capture decodes without --swap-cameras, in metres, on the true
// surface (measured against the stone mesh the capture writes in cam1's frame).
#include <gtest/gtest.h>

#include <algorithm>
#include <cstdio>
#include <filesystem>
#include <vector>

#include "anascan/processing/io/ply.hpp"
#include "anascan/sim/ray_caster.hpp"
#include "cli_runner.hpp"

namespace anascan::test {
namespace {

namespace fs = std::filesystem;
using testing_util::CliRun;
using testing_util::run_cli;

class SimSlCli : public testing_util::Cli {
protected:
    // A 320 x 240 crop of the rig's cameras (full focal length, 1 m): a fast capture.
    void capture() {
        const CliRun run = run_cli(
            "sim sl-capture small-block --step-mm 2 --camera-width 320 "
            "--camera-height 240 --out " +
            (dir_ / "cap").string());
        ASSERT_EQ(run.exit_code, 0) << run.output;
    }
    CliRun decode(const std::string& extra) {
        const fs::path cap = dir_ / "cap";
        return run_cli("sl decode --calibration " + (cap / "calibration.yml").string() +
                       " --cam1 '" + (cap / "pattern_cam1_im*.png").string() + "' --cam2 '" +
                       (cap / "pattern_cam2_im*.png").string() + "' --out " +
                       (dir_ / "cloud.ply").string() + " " + extra);
    }
};

// The decoded cloud against the stone mesh the capture wrote (both in cam1's frame).
struct OnStone {
    std::size_t points = 0;
    std::size_t near = 0;    ///< Within 5 mm of the stone (the crop also sees some ground).
    std::size_t within = 0;  ///< Of those, within 0.3 mm.
    double median_depth_m = 0.0;
};

OnStone measure(const fs::path& cloud_ply, const fs::path& stone_ply) {
    auto cloud = io::read_ply(cloud_ply);
    auto stone = io::read_ply(stone_ply);
    EXPECT_TRUE(cloud && stone);
    if (!cloud || !stone) return {};
    const sim::RayCaster truth =
        sim::RayCaster::create(Mesh{.vertices = stone->cloud, .triangles = stone->triangles})
            .value();
    OnStone m{.points = cloud->cloud.size()};
    std::vector<double> depth_m;
    for (std::size_t i = 0; i < cloud->cloud.size(); ++i) {
        const Eigen::Vector3d p = cloud->cloud.world_position(i);
        depth_m.push_back(p.z());
        const auto nearest = truth.closest_point(p, 0.005);
        if (!nearest) continue;
        ++m.near;
        if (nearest->distance_m <= 3e-4) ++m.within;
    }
    if (depth_m.empty()) return m;
    std::nth_element(depth_m.begin(), depth_m.begin() + depth_m.size() / 2, depth_m.end());
    m.median_depth_m = depth_m[depth_m.size() / 2];
    return m;
}

// No layout flags: the capture's calibration.yml records it (proj_size, pattern_phase_*).
TEST_F(SimSlCli, CaptureDecodesOnTheStoneInMetresWithoutSwap) {
    capture();
    const CliRun run = decode("");
    ASSERT_EQ(run.exit_code, 0) << run.output;
    EXPECT_NE(run.output.find("4 phase steps of period 8 px (from the calibration file)"),
              std::string::npos)
        << run.output;
    EXPECT_EQ(run.output.find("--swap-cameras"), std::string::npos) << run.output;
    const OnStone m = measure(dir_ / "cloud.ply", dir_ / "cap" / "stone_in_cam1.ply");
    std::printf(
        "sl decode of sim sl-capture: %zu points, median depth %.3f m, %zu within 5 mm "
        "of the stone, %.2f %% of those within 0.3 mm\n",
        m.points, m.median_depth_m, m.near, 100.0 * double(m.within) / double(m.near));
    ASSERT_GT(m.points, 20000u) << run.output;
    EXPECT_NEAR(m.median_depth_m, 1.0, 0.15);  // Metres: the rig stands 1 m from the block.
    EXPECT_GT(m.near, m.points * 8 / 10);
    EXPECT_GE(double(m.within), 0.95 * double(m.near));
    // The same measurement as a command (every point, ground ones included).
    const CliRun dist = run_cli("sim surface-distance " + (dir_ / "cloud.ply").string() +
                                " --mesh " + (dir_ / "cap" / "stone_in_cam1.ply").string());
    EXPECT_EQ(dist.exit_code, 0) << dist.output;
    EXPECT_NE(dist.output.find(" within 0.30 mm of "), std::string::npos) << dist.output;
    // A cloud is no mesh: the error names the file.
    const CliRun bad = run_cli("sim surface-distance " + (dir_ / "cloud.ply").string() +
                               " --mesh " + (dir_ / "cloud.ply").string());
    EXPECT_NE(bad.exit_code, 0);
    EXPECT_NE(bad.output.find("cloud.ply: no triangles"), std::string::npos) << bad.output;
}

// The statue data's --swap-cameras is wrong here: the mirrored rig still triangulates
// (small ray gaps), but the points leave the stone. (Layout flags override the file's.)
TEST_F(SimSlCli, SwappingTheCamerasMovesThePointsOffTheStone) {
    capture();
    const CliRun run = decode("--phase-steps 4 --phase-period 8 --swap-cameras");
    const OnStone m = measure(dir_ / "cloud.ply", dir_ / "cap" / "stone_in_cam1.ply");
    std::printf(
        "with --swap-cameras: %zu points, median depth %.3f m, %zu within 5 mm of the "
        "stone, %zu within 0.3 mm\n",
        m.points, m.median_depth_m, m.near, m.within);
    EXPECT_LT(double(m.within), 0.1 * double(m.points)) << run.output;
}

}  // namespace
}  // namespace anascan::test
