// Normals + orientation on 100k points: ours against Open3D's EstimateNormals with
// OrientNormalsTowardsCameraLocation / OrientNormalsConsistentTangentPlane, same k.
// Input: the first 100k points of the Stanford bunny scans (bun*.ply, merged in their
// .conf frame), or a synthetic wavy surface when the data is absent (printed as context).

#include <benchmark/benchmark.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <string>

#include "anascan/processing/cleaning/normals.hpp"
#include "anascan/processing/io/ply.hpp"
#include "anascan/processing/io/stanford_conf.hpp"

#if ANASCAN_HAVE_OPEN3D
#include <open3d/geometry/KDTreeSearchParam.h>
#include <open3d/geometry/PointCloud.h>
#endif

namespace {

constexpr std::size_t kPoints = 100000;
constexpr int kNeighbors = 16;  // Open3D's KNN(k) counts the point itself: ours k - 1.

anascan::PointCloud load_bunny(const std::filesystem::path& dir) {
    anascan::PointCloud merged;
    const auto conf = anascan::io::read_conf(dir / "bun.conf");
    if (!conf) return merged;
    for (const auto& entry : conf->entries) {
        auto ply = anascan::io::read_ply(dir / entry.file);
        if (!ply) return {};
        for (auto& p : ply->cloud.positions) {
            p = (entry.T_world_scan * p.cast<double>()).cast<float>();
        }
        append(merged, ply->cloud);
        if (merged.size() >= kPoints) break;
    }
    return merged;
}

anascan::PointCloud wavy_surface() {
    anascan::PointCloud cloud;
    for (int i = 0; i < 317; ++i) {
        for (int j = 0; j < 317; ++j) {
            const float x = float(i) * 0.0005f, y = float(j) * 0.0005f;
            cloud.positions.emplace_back(x, y, 0.01f * std::sin(x * 40.0f) * std::cos(y * 30.0f));
        }
    }
    return cloud;
}

const anascan::PointCloud& input() {
    static const anascan::PointCloud cloud = [] {
        anascan::PointCloud c = load_bunny(ANASCAN_BUNNY_DIR);
        const bool bunny = c.size() >= kPoints;
        if (!bunny) c = wavy_surface();
        c.positions.resize(std::min(c.size(), kPoints));
        c.normals.clear();
        benchmark::AddCustomContext(
            "input", bunny ? "stanford bunny bun*.ply (conf frame)" : "synthetic wavy surface");
        benchmark::AddCustomContext("points", std::to_string(c.size()));
        return c;
    }();
    return cloud;
}

const Eigen::Vector3f kSensor(0.0f, 0.0f, 1.0f);

void BM_Anascan_NormalsTowardSensor(benchmark::State& state) {
    for (auto _ : state) {
        anascan::PointCloud cloud = input();
        anascan::estimate_normals(cloud, {.k_neighbors = kNeighbors - 1});
        anascan::orient_toward(cloud, kSensor);
        benchmark::DoNotOptimize(cloud.normals.data());
    }
}

void BM_Anascan_NormalsConsistent(benchmark::State& state) {
    for (auto _ : state) {
        anascan::PointCloud cloud = input();
        const auto result =
            anascan::estimate_normals(cloud, {.k_neighbors = kNeighbors - 1, .keep_graph = true});
        anascan::orient_consistently(cloud, result.graph);
        benchmark::DoNotOptimize(cloud.normals.data());
    }
}

BENCHMARK(BM_Anascan_NormalsTowardSensor)->Unit(benchmark::kMillisecond)->UseRealTime();
BENCHMARK(BM_Anascan_NormalsConsistent)->Unit(benchmark::kMillisecond)->UseRealTime();

#if ANASCAN_HAVE_OPEN3D
open3d::geometry::PointCloud to_open3d(const anascan::PointCloud& cloud) {
    open3d::geometry::PointCloud out;
    for (const auto& p : cloud.positions) out.points_.push_back(p.cast<double>());
    return out;
}

void BM_Open3D_NormalsTowardSensor(benchmark::State& state) {
    const open3d::geometry::PointCloud source = to_open3d(input());
    for (auto _ : state) {
        open3d::geometry::PointCloud cloud = source;
        cloud.EstimateNormals(open3d::geometry::KDTreeSearchParamKNN(kNeighbors));
        cloud.OrientNormalsTowardsCameraLocation(kSensor.cast<double>());
        benchmark::DoNotOptimize(cloud.normals_.data());
    }
}

void BM_Open3D_NormalsConsistent(benchmark::State& state) {
    const open3d::geometry::PointCloud source = to_open3d(input());
    for (auto _ : state) {
        open3d::geometry::PointCloud cloud = source;
        cloud.EstimateNormals(open3d::geometry::KDTreeSearchParamKNN(kNeighbors));
        cloud.OrientNormalsConsistentTangentPlane(kNeighbors);
        benchmark::DoNotOptimize(cloud.normals_.data());
    }
}

BENCHMARK(BM_Open3D_NormalsTowardSensor)->Unit(benchmark::kMillisecond)->UseRealTime();
BENCHMARK(BM_Open3D_NormalsConsistent)->Unit(benchmark::kMillisecond)->UseRealTime()->Iterations(1);
#endif

}  // namespace

// Loads the input first so that its description is printed with the run's context.
int main(int argc, char** argv) {
    benchmark::Initialize(&argc, argv);
    if (benchmark::ReportUnrecognizedArguments(argc, argv)) return 1;
    input();
    benchmark::RunSpecifiedBenchmarks();
    benchmark::Shutdown();
    return 0;
}
