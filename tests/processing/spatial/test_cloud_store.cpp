// CloudStore: clouds in memory, or spilled to PLY files and reloaded on demand (LRU), with
// clear errors for unknown keys and unreadable files.
#include <gtest/gtest.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <string>

#include "anascan/processing/spatial/cloud_store.hpp"

namespace anascan {
namespace {

namespace fs = std::filesystem;

PointCloud numbered_cloud(int n) {
    PointCloud cloud;
    cloud.origin_m = Eigen::Vector3d(100.0 + n, -2.5, 0.125);  // Far origin: must round-trip.
    for (int i = 0; i < 50 + n; ++i) {
        cloud.positions.emplace_back(0.001f * float(i), 0.002f * float(n), -0.003f * float(i));
        cloud.normals.emplace_back(0.0f, 0.0f, 1.0f);
    }
    return cloud;
}

fs::path fresh_directory(const std::string& name) {
    const fs::path dir =
        fs::temp_directory_path() / ("anascan_test_" + name + "_" + std::to_string(getpid()));
    fs::remove_all(dir);
    return dir;
}

bool same(const PointCloud& a, const PointCloud& b) {
    return a.origin_m == b.origin_m && a.positions == b.positions && a.normals == b.normals;
}

TEST(CloudStore, InMemoryKeepsEveryCloudAndWritesNothing) {
    CloudStore store;
    for (int k = 0; k < 5; ++k) ASSERT_TRUE(store.put(std::size_t(k), numbered_cloud(k)));
    EXPECT_FALSE(store.spills());
    EXPECT_EQ(store.loaded_count(), 5u);
    for (int k = 0; k < 5; ++k) {
        const auto cloud = store.get(std::size_t(k));
        ASSERT_TRUE(cloud);
        EXPECT_TRUE(same(**cloud, numbered_cloud(k)));
    }
    EXPECT_EQ(store.reload_count(), 0u);
}

TEST(CloudStore, SpillsKeepsAtMostMaxLoadedAndReloadsExactly) {
    const fs::path dir = fresh_directory("cloud_store_spill");
    {
        CloudStore store({.directory = dir, .max_loaded = 2});
        for (int k = 0; k < 4; ++k) ASSERT_TRUE(store.put(std::size_t(k), numbered_cloud(k)));
        EXPECT_TRUE(store.spills());
        EXPECT_EQ(store.loaded_count(), 2u);
        for (int k = 0; k < 4; ++k) {
            const auto cloud = store.get(std::size_t(k));
            ASSERT_TRUE(cloud) << cloud.error().message;
            EXPECT_TRUE(same(**cloud, numbered_cloud(k))) << k;
            EXPECT_LE(store.loaded_count(), 2u);
        }
        // 0 and 1 were evicted by 2 and 3, reloading them evicted 2 and 3 in turn.
        EXPECT_EQ(store.reload_count(), 4u);
        const auto again = store.get(3);  // Most recent: still loaded.
        ASSERT_TRUE(again);
        EXPECT_EQ(store.reload_count(), 4u);
        EXPECT_FALSE(fs::is_empty(dir));
    }
    EXPECT_TRUE(fs::is_empty(dir)) << "spill files are removed with the store";
    fs::remove_all(dir);
}

TEST(CloudStore, UnknownKeyAndUnreadableFileAreClearErrors) {
    const fs::path dir = fresh_directory("cloud_store_errors");
    CloudStore store({.directory = dir, .max_loaded = 1});
    const auto missing = store.get(7);
    ASSERT_FALSE(missing);
    EXPECT_NE(missing.error().message.find("key 7"), std::string::npos) << missing.error().message;

    ASSERT_TRUE(store.put(0, numbered_cloud(0)));
    ASSERT_TRUE(store.put(1, numbered_cloud(1)));  // Evicts 0 from memory.
    const fs::path file = dir / "cloud_0.ply";
    ASSERT_TRUE(fs::exists(file));
    std::ofstream(file, std::ios::trunc) << "not a ply file";
    const auto corrupt = store.get(0);
    ASSERT_FALSE(corrupt);
    EXPECT_NE(corrupt.error().message.find("cloud_0.ply"), std::string::npos)
        << corrupt.error().message;
    store.remove_files();
    fs::remove_all(dir);
}

TEST(CloudStore, UnwritableDirectoryIsAClearError) {
    const fs::path blocker = fresh_directory("cloud_store_blocker");
    std::ofstream(blocker) << "a file where the directory should be";
    CloudStore store({.directory = blocker / "sub", .max_loaded = 1});
    const auto put = store.put(0, numbered_cloud(0));
    ASSERT_FALSE(put);
    EXPECT_NE(put.error().message.find("anascan_test_cloud_store_blocker"), std::string::npos)
        << put.error().message;
    fs::remove(blocker);
}

}  // namespace
}  // namespace anascan
