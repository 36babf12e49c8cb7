#pragma once
// Small scans and scratch session folders for the session store tests.
#include <gtest/gtest.h>
#include <unistd.h>

#include <filesystem>
#include <random>
#include <string>

#include "anascan/processing/core/scan.hpp"

namespace anascan::testing_util {

/// A scan of `n` random points with normals, intensity and confidence (fixed seed).
inline Scan make_scan(std::size_t n, unsigned seed, const std::string& device = "sim:test#0") {
    std::mt19937 rng(seed);
    std::uniform_real_distribution<float> u(-0.2f, 0.2f);
    Scan scan;
    scan.meta.device_id = device;
    scan.meta.device_kind = DeviceKind::kStructuredLight;
    scan.meta.sensor_origin_scan_m = Eigen::Vector3d(0.1, -0.2, 1.5);
    scan.meta.settings_json = R"({"exposure_ms":12})";
    scan.meta.time = std::chrono::system_clock::now();
    scan.cloud.origin_m = Eigen::Vector3d(1000.5, 2000.25, 3.0);
    for (std::size_t i = 0; i < n; ++i) {
        scan.cloud.positions.emplace_back(u(rng), u(rng), u(rng));
        scan.cloud.normals.push_back(Eigen::Vector3f(u(rng), u(rng), 1.0f).normalized());
        scan.cloud.intensity.push_back(u(rng) + 1.0f);
        scan.cloud.confidence.push_back(0.5f + u(rng));
    }
    return scan;
}

/// A pose with a rotation and a translation that differ per `k`.
inline Pose make_test_pose(int k) {
    Pose T = Pose::Identity();
    T.rotate(Eigen::AngleAxisd(0.1 * k + 0.05, Eigen::Vector3d(1, 2, 3).normalized()));
    T.translation() = Eigen::Vector3d(0.01 * k, -0.02 * k, 0.3 + 1e-7 * k);
    return T;
}

/// A fresh scratch folder per test, removed afterwards.
class SessionFolder : public ::testing::Test {
protected:
    void SetUp() override {
        const auto* info = ::testing::UnitTest::GetInstance()->current_test_info();
        root_ = std::filesystem::path(::testing::TempDir()) /
                ("session-" + std::to_string(::getpid()) + "-" + info->name());
        std::filesystem::remove_all(root_);
        std::filesystem::create_directories(root_);
        dir_ = root_ / "s1";
    }
    void TearDown() override {
        std::error_code ec;
        std::filesystem::permissions(root_, std::filesystem::perms::owner_all,
                                     std::filesystem::perm_options::add, ec);
        if (std::filesystem::exists(dir_ / "scans"))
            std::filesystem::permissions(dir_ / "scans", std::filesystem::perms::owner_all,
                                         std::filesystem::perm_options::add, ec);
        std::filesystem::remove_all(root_, ec);
    }
    std::filesystem::path root_, dir_;
};

}  // namespace anascan::testing_util
