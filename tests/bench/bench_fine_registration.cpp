// Fine registration of the Stanford bunny pair bun045 -> bun000 from a start 5° and 5 mm
// off bun.conf: anascan's register_fine (sampling, k-d tree build and all iterations
// included) against Open3D's RegistrationICP (point-to-plane, 5 mm max correspondence
// distance, default convergence criteria) in the same run with the same target normals.
// Normal estimation is done once, outside the timed loops. Counters: final error against
// bun.conf (rotation_deg, translation_mm) and iterations.
#include <benchmark/benchmark.h>

#include <Eigen/Geometry>
#include <filesystem>
#include <memory>
#include <numbers>
#include <optional>

#include "anascan/processing/core/pose.hpp"
#include "anascan/processing/io/ply.hpp"
#include "anascan/processing/io/stanford_conf.hpp"
#include "anascan/processing/registration/fine/fine_registration.hpp"
#include "anascan/processing/spatial/kdtree.hpp"
#include "test_normals_util.hpp"

#if ANASCAN_BENCH_OPEN3D
#include <open3d/geometry/PointCloud.h>
#include <open3d/pipelines/registration/Registration.h>
#include <open3d/pipelines/registration/TransformationEstimation.h>
#include <open3d/utility/Logging.h>
#endif

namespace anascan {
namespace {

namespace fs = std::filesystem;

constexpr double kWarmUpSeconds = 0.5;
constexpr double kMaxCorrespondenceDistanceM = 0.005;

struct BunnyPair {
    PointCloud source;  // bun045 with PCA normals (scan frame).
    PointCloud target;  // bun000 with PCA normals (scan frame).
    Pose truth;         // T_000_045 from bun.conf.
    Pose initial;       // truth moved 5° about (1 1 0) through the centroid and 5 mm.
};

Pose five_degrees_five_millimetres_off(const PointCloud& source, const Pose& truth) {
    Eigen::Vector3d centroid = Eigen::Vector3d::Zero();
    for (const Eigen::Vector3f& p : source.positions) centroid += p.cast<double>();
    centroid = truth * (centroid / static_cast<double>(source.size()));
    const Eigen::AngleAxisd turn(5.0 * std::numbers::pi / 180.0,
                                 Eigen::Vector3d(1, 1, 0).normalized());
    return Eigen::Translation3d(0.005 * Eigen::Vector3d(-1, 0, 1).normalized()) *
           Eigen::Translation3d(centroid) * turn * Eigen::Translation3d(-centroid) * truth;
}

// Loaded once; nullopt when the data is absent.
const std::optional<BunnyPair>& bunny() {
    static const std::optional<BunnyPair> pair = []() -> std::optional<BunnyPair> {
        const fs::path dir = fs::path(ANASCAN_SHARED_DATA_DIR) / "stanford-bunny-range-scans/data";
        auto conf = io::read_conf(dir / "bun.conf");
        auto target = io::read_ply(dir / "bun000.ply");
        auto source = io::read_ply(dir / "bun045.ply");
        if (!conf || !target || !source) return std::nullopt;
        const io::ConfEntry* e000 = conf->find("bun000.ply");
        const io::ConfEntry* e045 = conf->find("bun045.ply");
        if (e000 == nullptr || e045 == nullptr) return std::nullopt;
        BunnyPair p{std::move(source->cloud), std::move(target->cloud),
                    e000->T_world_scan.inverse() * e045->T_world_scan, Pose::Identity()};
        test::estimate_normals_pca(p.target, Eigen::Vector3f::UnitZ());
        test::estimate_normals_pca(p.source, Eigen::Vector3f::UnitZ());
        p.initial = five_degrees_five_millimetres_off(p.source, p.truth);
        return p;
    }();
    return pair;
}

void report_error(benchmark::State& state, const Pose& truth, const Pose& estimate,
                  int iterations) {
    const PoseDifference error = pose_difference(truth, estimate);
    state.counters["rotation_deg"] = error.rotation_deg;
    state.counters["translation_mm"] = error.translation_m * 1e3;
    state.counters["iterations"] = iterations;
}

void BM_AnascanFineRegistration(benchmark::State& state) {
    if (!bunny()) return state.SkipWithError("Stanford bunny scans not found");
    const BunnyPair& p = *bunny();
    const FineRegistrationConfig config{.max_correspondence_distance_m =
                                            kMaxCorrespondenceDistanceM};
    FineRegistrationResult result;
    for (auto _ : state) {
        result = register_fine(p.source, p.target, p.initial, config);
        benchmark::DoNotOptimize(result.T_target_source);
    }
    if (result.status != FineRegistrationStatus::kConverged) state.SkipWithError("not converged");
    report_error(state, p.truth, result.T_target_source, result.iterations);
}

// Without the symmetric polish (target normals only, as before it existed).
void BM_AnascanFineRegistrationNoPolish(benchmark::State& state) {
    if (!bunny()) return state.SkipWithError("Stanford bunny scans not found");
    const BunnyPair& p = *bunny();
    const FineRegistrationConfig config{
        .max_correspondence_distance_m = kMaxCorrespondenceDistanceM, .symmetric_polish = false};
    FineRegistrationResult result;
    for (auto _ : state) {
        result = register_fine(p.source, p.target, p.initial, config);
        benchmark::DoNotOptimize(result.T_target_source);
    }
    report_error(state, p.truth, result.T_target_source, result.iterations);
}

// The session case: the target's k-d tree is built once and reused.
void BM_AnascanFineRegistrationPrebuiltTree(benchmark::State& state) {
    if (!bunny()) return state.SkipWithError("Stanford bunny scans not found");
    const BunnyPair& p = *bunny();
    const KdTree tree(p.target.positions);
    FineRegistrationResult result;
    for (auto _ : state) {
        result = register_fine(p.source, p.target, tree, p.initial, {});
        benchmark::DoNotOptimize(result.T_target_source);
    }
    report_error(state, p.truth, result.T_target_source, result.iterations);
}

BENCHMARK(BM_AnascanFineRegistration)->Unit(benchmark::kMillisecond)->MinWarmUpTime(kWarmUpSeconds);
BENCHMARK(BM_AnascanFineRegistrationNoPolish)
    ->Unit(benchmark::kMillisecond)
    ->MinWarmUpTime(kWarmUpSeconds);
BENCHMARK(BM_AnascanFineRegistrationPrebuiltTree)
    ->Unit(benchmark::kMillisecond)
    ->MinWarmUpTime(kWarmUpSeconds);

#if ANASCAN_BENCH_OPEN3D
std::shared_ptr<open3d::geometry::PointCloud> to_open3d(const PointCloud& cloud) {
    auto out = std::make_shared<open3d::geometry::PointCloud>();
    for (std::size_t i = 0; i < cloud.size(); ++i) {
        out->points_.push_back(cloud.world_position(i));
        out->normals_.push_back(cloud.normals[i].cast<double>());
    }
    return out;
}

void BM_Open3dRegistrationIcpPointToPlane(benchmark::State& state) {
    if (!bunny()) return state.SkipWithError("Stanford bunny scans not found");
    namespace reg = open3d::pipelines::registration;
    open3d::utility::SetVerbosityLevel(open3d::utility::VerbosityLevel::Error);
    const BunnyPair& p = *bunny();
    const auto source = to_open3d(p.source);
    const auto target = to_open3d(p.target);  // The same target normals as ours.
    reg::RegistrationResult result;
    for (auto _ : state) {
        result =
            reg::RegistrationICP(*source, *target, kMaxCorrespondenceDistanceM, p.initial.matrix(),
                                 reg::TransformationEstimationPointToPlane());
        benchmark::DoNotOptimize(result.transformation_);
    }
    report_error(state, p.truth, Pose(result.transformation_), -1);
}

BENCHMARK(BM_Open3dRegistrationIcpPointToPlane)
    ->Unit(benchmark::kMillisecond)
    ->MinWarmUpTime(kWarmUpSeconds);
#endif

}  // namespace
}  // namespace anascan

BENCHMARK_MAIN();
