// PLY read and write of a 1-million-point binary little-endian cloud with normals (float x y
// z nx ny nz), anascan against Open3D on the same file in the same run.
#include <benchmark/benchmark.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <random>
#include <string>

#include "anascan/processing/io/file_bytes.hpp"
#include "anascan/processing/io/ply.hpp"

#if ANASCAN_BENCH_OPEN3D
#include <open3d/geometry/PointCloud.h>
#include <open3d/io/PointCloudIO.h>
#include <open3d/utility/Logging.h>
#endif

namespace {

namespace fs = std::filesystem;
constexpr std::size_t kPoints = 1'000'000;

// The benchmark's files, in a fresh temporary folder removed at exit.
struct BenchFiles {
    fs::path dir;
    fs::path input;
    anascan::PointCloud cloud;

    BenchFiles() {
        dir = fs::temp_directory_path() / ("anascan_bench_ply_" + std::to_string(::getpid()));
        fs::create_directories(dir);
        input = dir / "cloud_1m_normals.ply";
        std::mt19937 rng(7);
        std::uniform_real_distribution<float> coord(-50.0f, 50.0f);
        cloud.positions.resize(kPoints);
        cloud.normals.resize(kPoints);
        for (std::size_t i = 0; i < kPoints; ++i) {
            cloud.positions[i] = {coord(rng), coord(rng), coord(rng)};
            cloud.normals[i] = Eigen::Vector3f(coord(rng), coord(rng), coord(rng)).normalized();
        }
        if (!anascan::io::write_ply(input, cloud)) std::abort();
    }
    ~BenchFiles() {
        std::error_code ignored;
        fs::remove_all(dir, ignored);
    }
};

BenchFiles& files() {
    static BenchFiles instance;
    return instance;
}

void set_bytes(benchmark::State& state) {
    state.SetBytesProcessed(static_cast<std::int64_t>(state.iterations()) *
                            static_cast<std::int64_t>(fs::file_size(files().input)));
}

void BM_AnascanReadPly(benchmark::State& state) {
    for (auto _ : state) {
        auto data = anascan::io::read_ply(files().input);
        if (!data || data->cloud.size() != kPoints) state.SkipWithError("read_ply failed");
        benchmark::DoNotOptimize(data);
    }
    set_bytes(state);
}

// The parse alone, from bytes already in memory (what read_ply adds is the file read).
void BM_AnascanParsePlyInMemory(benchmark::State& state) {
    const auto bytes = anascan::io::read_file_bytes(files().input);
    if (!bytes) std::abort();
    for (auto _ : state) {
        auto data = anascan::io::parse_ply(*bytes, "in-memory.ply");
        if (!data || data->cloud.size() != kPoints) state.SkipWithError("parse_ply failed");
        benchmark::DoNotOptimize(data);
    }
    set_bytes(state);
}

// write_ply is crash-safe: temporary file, fsync, rename, fsync of the folder.
void BM_AnascanWritePly(benchmark::State& state) {
    const fs::path out = files().dir / "anascan_out.ply";
    for (auto _ : state) {
        if (!anascan::io::write_ply(out, files().cloud)) state.SkipWithError("write_ply failed");
    }
    set_bytes(state);
}

// The same bytes written the way Open3D writes (plain stream, no fsync): like for like.
void BM_AnascanSerializeAndWriteNoSync(benchmark::State& state) {
    const fs::path out = files().dir / "anascan_nosync.ply";
    for (auto _ : state) {
        const std::vector<char> bytes = anascan::io::serialize_ply(files().cloud, {}, {});
        std::ofstream file(out, std::ios::binary);
        file.write(bytes.data(), static_cast<std::streamsize>(bytes.size()));
        if (!file) state.SkipWithError("write failed");
    }
    set_bytes(state);
}

#if ANASCAN_BENCH_OPEN3D
void BM_Open3dReadPly(benchmark::State& state) {
    open3d::utility::SetVerbosityLevel(open3d::utility::VerbosityLevel::Error);
    for (auto _ : state) {
        open3d::geometry::PointCloud cloud;
        if (!open3d::io::ReadPointCloud(files().input.string(), cloud) ||
            cloud.points_.size() != kPoints) {
            state.SkipWithError("Open3D ReadPointCloud failed");
        }
        benchmark::DoNotOptimize(cloud);
    }
    set_bytes(state);
}

void BM_Open3dWritePly(benchmark::State& state) {
    open3d::geometry::PointCloud cloud;
    open3d::io::ReadPointCloud(files().input.string(), cloud);
    const std::string out = (files().dir / "open3d_out.ply").string();
    for (auto _ : state) {
        if (!open3d::io::WritePointCloud(out, cloud)) state.SkipWithError("Open3D write failed");
    }
    set_bytes(state);
}
#endif

constexpr double kWarmUpSeconds = 0.5;

BENCHMARK(BM_AnascanReadPly)->Unit(benchmark::kMillisecond)->MinWarmUpTime(kWarmUpSeconds);
BENCHMARK(BM_AnascanParsePlyInMemory)->Unit(benchmark::kMillisecond)->MinWarmUpTime(kWarmUpSeconds);
BENCHMARK(BM_AnascanWritePly)->Unit(benchmark::kMillisecond)->MinWarmUpTime(kWarmUpSeconds);
BENCHMARK(BM_AnascanSerializeAndWriteNoSync)
    ->Unit(benchmark::kMillisecond)
    ->MinWarmUpTime(kWarmUpSeconds);
#if ANASCAN_BENCH_OPEN3D
BENCHMARK(BM_Open3dReadPly)->Unit(benchmark::kMillisecond)->MinWarmUpTime(kWarmUpSeconds);
BENCHMARK(BM_Open3dWritePly)->Unit(benchmark::kMillisecond)->MinWarmUpTime(kWarmUpSeconds);
#endif

}  // namespace

int main(int argc, char** argv) {
    benchmark::Initialize(&argc, argv);
    if (benchmark::ReportUnrecognizedArguments(argc, argv)) return 1;
    files();  // write the input before timing anything
    benchmark::RunSpecifiedBenchmarks();
    benchmark::Shutdown();
    return 0;
}
