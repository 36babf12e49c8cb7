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
        const CliRun run = run_cli("sim sl-capture small-block --step-mm 2 --camera-width 320 "
                                   "--camera-height 240 --out " + (dir_ / "cap").string());
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

TEST_F(SimSlCli, CaptureDecodesOnTheStoneInMetresWithoutSwap) {
    capture();
    const CliRun run = decode("--phase-steps 4 --phase-period 8");
    ASSERT_EQ(run.exit_code, 0) << run.output;
    EXPECT_EQ(run.output.find("--swap-cameras"), std::string::npos) << run.output;
    auto cloud = io::read_ply(dir_ / "cloud.ply");
    ASSERT_TRUE(cloud) << cloud.error().message;
    auto stone_ply = io::read_ply(dir_ / "cap" / "stone_in_cam1.ply");
    ASSERT_TRUE(stone_ply) << stone_ply.error().message;
    const Mesh stone{.vertices = stone_ply->cloud, .triangles = stone_ply->triangles};
    const sim::RayCaster truth = sim::RayCaster::create(stone).value();
    // Points on the stone (the crop also sees some ground): distance to the stone mesh.
    std::size_t on_stone = 0, within = 0;
    std::vector<double> depth_m;
    for (std::size_t i = 0; i < cloud->cloud.size(); ++i) {
        const Eigen::Vector3d p = cloud->cloud.world_position(i);
        depth_m.push_back(p.z());
        const auto nearest = truth.closest_point(p, 0.005);
        if (!nearest) continue;
        ++on_stone;
        if (nearest->distance_m <= 3e-4) ++within;
    }
    ASSERT_GT(depth_m.size(), 20000u) << run.output;
    std::nth_element(depth_m.begin(), depth_m.begin() + depth_m.size() / 2, depth_m.end());
    const double median_depth_m = depth_m[depth_m.size() / 2];
    std::printf("sl decode of sim sl-capture: %zu points, median depth %.3f m, %zu within 5 mm "
                "of the stone, %.2f %% of those within 0.3 mm\n",
                cloud->cloud.size(), median_depth_m, on_stone, 100.0 * within / on_stone);
    EXPECT_NEAR(median_depth_m, 1.0, 0.15);  // Metres: the rig stands 1 m from the block.
    EXPECT_GT(on_stone, cloud->cloud.size() * 8 / 10);
    EXPECT_GE(double(within), 0.95 * double(on_stone));
}

TEST_F(SimSlCli, SwappedCamerasAreFlagged) {
    capture();
    const CliRun run = decode("--phase-steps 4 --phase-period 8 --swap-cameras");
    EXPECT_NE(run.output.find("--swap-cameras"), std::string::npos) << run.output;
}

}  // namespace
}  // namespace anascan::test
