#include <gtest/gtest.h>

#include <cmath>
#include <set>
#include <tuple>

#include "anascan/sim/box_stone_scanner.hpp"

namespace anascan::sim {
namespace {

// Coarser than the default so the suite stays fast; same geometry.
BoxStoneScanConfig test_config() {
    return BoxStoneScanConfig{.angular_step_deg = 0.5, .noise_sigma_m = 0.0002, .seed = 9};
}

// Signed distance from p to the surface of the centred box with half sizes `half`.
double box_sdf(const Eigen::Vector3d& p, const Eigen::Vector3d& half) {
    const Eigen::Vector3d q = p.cwiseAbs() - half;
    return q.cwiseMax(0.0).norm() + std::min(q.maxCoeff(), 0.0);
}

TEST(BoxStoneScanner, ProducesOneScanPerViewWithMetadata) {
    const BoxStoneScanConfig config = test_config();
    const std::vector<Scan> scans = scan_box_stone(config);
    ASSERT_EQ(scans.size(), static_cast<std::size_t>(config.view_count));
    for (std::size_t v = 0; v < scans.size(); ++v) {
        const ScanMetadata& meta = scans[v].meta;
        EXPECT_EQ(meta.id, "box-view-0" + std::to_string(v));
        EXPECT_EQ(meta.sequence, static_cast<std::int64_t>(v));
        EXPECT_EQ(meta.device_id, "sim:box");
        EXPECT_EQ(meta.device_kind, DeviceKind::kStructuredLight);
        ASSERT_TRUE(meta.sensor_origin_scan_m.has_value());
        EXPECT_EQ(*meta.sensor_origin_scan_m, Eigen::Vector3d::Zero());
        ASSERT_TRUE(meta.T_world_scan.has_value());
        const Pose& T = *meta.T_world_scan;
        EXPECT_NEAR(T.linear().determinant(), 1.0, 1e-12);
        EXPECT_NEAR(T.translation().norm(), config.distance_m, 1e-12);
        // The sensor looks at the block centre along its +z.
        EXPECT_TRUE(T.linear().col(2).isApprox(-T.translation().normalized(), 1e-12));
        EXPECT_GT(scans[v].cloud.size(), 1000u);
        EXPECT_TRUE(scans[v].cloud.attributes_consistent());
        EXPECT_EQ(scans[v].cloud.normals.size(), scans[v].cloud.size());
    }
}

TEST(BoxStoneScanner, PointsLieOnTheBoxSurfaceInTheWorld) {
    const BoxStoneScanConfig config = test_config();
    const Eigen::Vector3d half = 0.5 * config.size_m;
    for (const Scan& scan : scan_box_stone(config)) {
        const Pose& T_world_scan = *scan.meta.T_world_scan;
        double worst = 0.0;
        for (std::size_t i = 0; i < scan.cloud.size(); ++i) {
            const Eigen::Vector3d p_world = T_world_scan * scan.cloud.world_position(i);
            worst = std::max(worst, std::abs(box_sdf(p_world, half)));
        }
        EXPECT_LE(worst, 5.0 * config.noise_sigma_m) << scan.meta.id;
    }
}

TEST(BoxStoneScanner, NoiselessPointsAreExactlyOnTheSurface) {
    BoxStoneScanConfig config = test_config();
    config.noise_sigma_m = 0.0;
    config.view_count = 3;
    const Eigen::Vector3d half = 0.5 * config.size_m;
    for (const Scan& scan : scan_box_stone(config)) {
        for (std::size_t i = 0; i < scan.cloud.size(); ++i) {
            const Eigen::Vector3d p_world = *scan.meta.T_world_scan * scan.cloud.world_position(i);
            ASSERT_LT(std::abs(box_sdf(p_world, half)), 1e-6) << scan.meta.id << " point " << i;
        }
    }
}

TEST(BoxStoneScanner, EachViewSeesAtLeastTwoFaces) {
    for (const Scan& scan : scan_box_stone(test_config())) {
        std::set<std::tuple<long, long, long>> faces;
        const Eigen::Matrix3d R_world_scan = scan.meta.T_world_scan->linear();
        for (const Eigen::Vector3f& n : scan.cloud.normals) {
            const Eigen::Vector3d n_world = R_world_scan * n.cast<double>();
            faces.emplace(std::lround(n_world.x()), std::lround(n_world.y()),
                          std::lround(n_world.z()));
        }
        EXPECT_GE(faces.size(), 2u) << scan.meta.id;
        EXPECT_LE(faces.size(), 3u) << scan.meta.id;  // A box shows at most 3 faces.
        // Elevated sensors see the top face.
        EXPECT_EQ(faces.count({0, 0, 1}), 1u) << scan.meta.id;
    }
}

TEST(BoxStoneScanner, NormalsAreUnitAndPointToTheSensor) {
    for (const Scan& scan : scan_box_stone(test_config())) {
        for (std::size_t i = 0; i < scan.cloud.size(); ++i) {
            const Eigen::Vector3f& n = scan.cloud.normals[i];
            ASSERT_NEAR(n.norm(), 1.0f, 1e-5f);
            // Sensor at the origin of the scan frame: the normal faces -p.
            ASSERT_LT(n.dot(scan.cloud.positions[i]), 0.0f) << scan.meta.id << " point " << i;
        }
    }
}

TEST(BoxStoneScanner, SameSeedGivesIdenticalScans) {
    const std::vector<Scan> a = scan_box_stone(test_config());
    const std::vector<Scan> b = scan_box_stone(test_config());
    ASSERT_EQ(a.size(), b.size());
    for (std::size_t v = 0; v < a.size(); ++v) {
        EXPECT_EQ(a[v].cloud.positions, b[v].cloud.positions);
        EXPECT_EQ(a[v].cloud.normals, b[v].cloud.normals);
        EXPECT_TRUE(a[v].meta.T_world_scan->isApprox(*b[v].meta.T_world_scan, 0.0));
    }
    BoxStoneScanConfig other = test_config();
    other.seed += 100;
    const std::vector<Scan> c = scan_box_stone(other);
    ASSERT_EQ(c[0].cloud.size(), a[0].cloud.size());
    EXPECT_NE(c[0].cloud.positions, a[0].cloud.positions);
}

TEST(BoxStoneScanner, DegenerateConfigsGiveNoPoints) {
    EXPECT_TRUE(scan_box_stone(BoxStoneScanConfig{.view_count = 0}).empty());
    const std::vector<Scan> scans =
        scan_box_stone(BoxStoneScanConfig{.view_count = 2, .angular_step_deg = 0.0});
    ASSERT_EQ(scans.size(), 2u);
    EXPECT_TRUE(scans[0].cloud.empty());
}

}  // namespace
}  // namespace anascan::sim
