// Block features of a 1 M-point simulated block (ours: CGAL Efficient RANSAC + adjacency,
// roughness, holes) against Open3D's SegmentPlane peeling six planes off the same points;
// and matching every face pair of 150 blocks (the paper's campaign size).
#include <benchmark/benchmark.h>

#include "anascan/processing/reassembly/block_features.hpp"
#include "anascan/processing/reassembly/face_matching.hpp"
#include "anascan/sim/monument.hpp"
#include "anascan/sim/stone_block.hpp"

#if ANASCAN_HAVE_OPEN3D
#include <open3d/geometry/PointCloud.h>
#endif

namespace {

namespace ra = anascan::reassembly;

// A 1.2 x 0.6 x 0.5 m block on a 1.6 mm grid: about 1 M vertices.
const anascan::Mesh& million_point_block() {
    static const anascan::Mesh mesh = [] {
        anascan::sim::StoneBlockConfig config;
        config.grid_step_m = 0.0016;
        return anascan::sim::make_stone_block(config);
    }();
    return mesh;
}

void BM_BlockFeatures_1M(benchmark::State& state) {
    const anascan::Mesh& mesh = million_point_block();
    for (auto _ : state) {
        const ra::BlockFeatures f = ra::extract_block_features(mesh, {});
        benchmark::DoNotOptimize(f.faces.data());
        state.counters["faces"] = double(f.faces.size());
    }
    state.counters["points"] = double(mesh.vertices.size());
}
BENCHMARK(BM_BlockFeatures_1M)->Unit(benchmark::kSecond)->Iterations(2);

#if ANASCAN_HAVE_OPEN3D
void BM_Open3D_SegmentPlane6_1M(benchmark::State& state) {
    const anascan::Mesh& mesh = million_point_block();
    open3d::geometry::PointCloud source;
    for (const auto& p : mesh.vertices.positions) source.points_.push_back(p.cast<double>());
    for (auto _ : state) {
        auto rest = std::make_shared<open3d::geometry::PointCloud>(source);
        for (int plane = 0; plane < 6 && rest->points_.size() > 100; ++plane) {
            auto [model, inliers] = rest->SegmentPlane(0.004, 3, 1000);
            rest = rest->SelectByIndex(inliers, true);
        }
        benchmark::DoNotOptimize(rest->points_.data());
    }
}
BENCHMARK(BM_Open3D_SegmentPlane6_1M)->Unit(benchmark::kSecond)->Iterations(2);
#endif

// Features of the octagon-wall blocks, repeated to 150 blocks.
const std::vector<ra::BlockFeatures>& campaign_features() {
    static const std::vector<ra::BlockFeatures> blocks = [] {
        auto m = anascan::sim::make_monument(*anascan::sim::named_monument("octagon-wall"));
        std::vector<ra::BlockFeatures> wall;
        for (const auto& b : m->blocks)
            wall.push_back(ra::extract_block_features(anascan::sim::block_mesh(b), {}));
        std::vector<ra::BlockFeatures> out;
        for (std::size_t i = 0; out.size() < 150; ++i) out.push_back(wall[i % wall.size()]);
        return out;
    }();
    return blocks;
}

void BM_MatchBlocks_150(benchmark::State& state) {
    const auto& blocks = campaign_features();
    for (auto _ : state) {
        const ra::MatchResult r = ra::match_blocks(blocks, {}, {});
        benchmark::DoNotOptimize(r.per_face.data());
    }
    state.counters["blocks"] = double(blocks.size());
}
BENCHMARK(BM_MatchBlocks_150)->Unit(benchmark::kSecond)->Iterations(2);

}  // namespace

BENCHMARK_MAIN();
