#include <gtest/gtest.h>
#include <unistd.h>

#include <filesystem>

#include "anascan/acquisition/assembly/assembly.hpp"
#include "anascan/processing/io/ply.hpp"
#include "anascan/processing/io/stanford_conf.hpp"
#include "anascan/sim/box_stone_scanner.hpp"

namespace anascan::acquisition {
namespace {

namespace fs = std::filesystem;

class Assembly : public ::testing::Test {
protected:
    void SetUp() override {
        dir_ = fs::path(::testing::TempDir()) / ("assembly-" + std::to_string(::getpid()));
        fs::remove_all(dir_);
        fs::create_directories(dir_);
    }
    void TearDown() override { fs::remove_all(dir_); }

    // Writes the simulated block scans and a .conf with `pose_error` applied to scan 1.
    fs::path write_scans(const Pose& pose_error) {
        io::StanfordConf conf;
        const std::vector<Scan> scans = sim::scan_box_stone({.view_count = 4});
        for (std::size_t i = 0; i < scans.size(); ++i) {
            const std::string file = scans[i].meta.id + ".ply";
            EXPECT_TRUE(io::write_ply(dir_ / file, scans[i].cloud).has_value());
            Pose T = *scans[i].meta.T_world_scan;
            if (i == 1) T = pose_error * T;
            conf.entries.push_back({file, T});
        }
        EXPECT_TRUE(io::write_conf(dir_ / "poses.conf", conf).has_value());
        return dir_ / "poses.conf";
    }

    fs::path dir_;
};

TEST_F(Assembly, TruePosesAgreeAtTheNoiseLevel) {
    auto report = assemble_from_conf(write_scans(Pose::Identity()), {});
    ASSERT_TRUE(report.has_value()) << report.error().message;
    EXPECT_EQ(report->scans.size(), 4u);
    ASSERT_FALSE(report->pairs.empty());
    // 0.1 mm range noise on both sides: neighbour distances stay well under a millimetre.
    EXPECT_LT(report->worst_pair_distance_m, 0.001);
    std::size_t total = 0;
    for (const AssembledScan& s : report->scans) total += s.points;
    EXPECT_EQ(report->model.size(), total);
}

TEST_F(Assembly, AWrongPoseShowsInTheWorstPair) {
    // Point-to-plane figures see motion across the surfaces: move across every face.
    const Pose error = make_pose(
        Eigen::Quaterniond(Eigen::AngleAxisd(0.02, Eigen::Vector3d(1, 2, 3).normalized())),
        Eigen::Vector3d(0.003, 0.003, 0.003));
    auto report = assemble_from_conf(write_scans(error), {});
    ASSERT_TRUE(report.has_value()) << report.error().message;
    EXPECT_GT(report->worst_pair_distance_m, 0.001);
}

TEST_F(Assembly, AMissingScanFileIsNamed) {
    const fs::path conf = write_scans(Pose::Identity());
    fs::remove(dir_ / "box-view-02.ply");
    auto report = assemble_from_conf(conf, {});
    ASSERT_FALSE(report.has_value());
    EXPECT_NE(report.error().message.find("box-view-02.ply"), std::string::npos)
        << report.error().message;
}

TEST_F(Assembly, ReportJsonCarriesUnitsInKeys) {
    auto report = assemble_from_conf(write_scans(Pose::Identity()), {});
    ASSERT_TRUE(report.has_value());
    const std::string json = report_to_json(*report);
    EXPECT_NE(json.find("\"median_distance_m\""), std::string::npos);
    EXPECT_NE(json.find("\"worst_pair_distance_m\""), std::string::npos);
}

}  // namespace
}  // namespace anascan::acquisition
