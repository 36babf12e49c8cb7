// Measures coverage on a simulated structured-light session (docs/coverage.md):
//   anascan_coverage_session [VIEWS [FLIP_AFTER [POINTS_PER_SCAN]]]
// Prints, after FLIP_AFTER / 2 views, FLIP_AFTER views and all views, the estimated and the
// ground-truth coverage, the largest holes and the time of compute_coverage. With
// POINTS_PER_SCAN, each scan is padded to that many points (its points repeated with a
// 0.1 mm jitter) to time a model of that size.

#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <random>

#include "coverage_session.hpp"

namespace {

using namespace anascan;

void pad(PointCloud& cloud, std::size_t points, std::mt19937& rng) {
    std::normal_distribution<float> jitter(0.0f, 0.0001f);
    const std::size_t n = cloud.size();
    for (std::size_t i = 0; n > 0 && cloud.size() < points; i = (i + 1) % n)
        cloud.positions.push_back(cloud.positions[i] +
                                  Eigen::Vector3f(jitter(rng), jitter(rng), jitter(rng)));
}

void report(const sim::test::CoverageSession& session, std::size_t count) {
    const auto views = sim::test::coverage_views(session, count);
    std::size_t points = 0;
    for (const auto& v : views) points += v.cloud->size();
    const auto start = std::chrono::steady_clock::now();
    const CoverageReport estimate = compute_coverage(views, {});
    const double seconds =
        std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    const CoverageReport truth = compute_coverage_on_surface(session.stone_world0, views, {});
    std::printf(
        "%zu views, %zu points: estimate %.2f %% of %.4f m2 (%s, %.3f s), truth %.2f %% "
        "of %.4f m2, difference %+.2f points\n",
        views.size(), points, 100 * estimate.fraction, estimate.surface_area_m2,
        to_string(estimate.status), seconds, 100 * truth.fraction, truth.surface_area_m2,
        100 * (estimate.fraction - truth.fraction));
    for (std::size_t h = 0; h < estimate.holes.size() && h < 4; ++h) {
        const CoverageHole& hole = estimate.holes[h];
        std::printf("  hole %zu: %.1f cm2 at (%.3f, %.3f, %.3f) m, normal (%.2f, %.2f, %.2f)\n",
                    h + 1, 1e4 * hole.area_m2, hole.centre_m.x(), hole.centre_m.y(),
                    hole.centre_m.z(), hole.normal.x(), hole.normal.y(), hole.normal.z());
    }
}

}  // namespace

int main(int argc, char** argv) {
    sim::test::CoverageSessionConfig config{.progress = true};
    if (argc > 1) config.views = std::atoi(argv[1]);
    if (argc > 2) config.flip_after = std::atoi(argv[2]);
    const std::size_t points_per_scan = argc > 3 ? std::strtoul(argv[3], nullptr, 10) : 0;
    auto session = sim::test::simulate_coverage_session(config);
    if (!session) {
        std::fprintf(stderr, "anascan_coverage_session: %s\n", session.error().message.c_str());
        return 1;
    }
    std::mt19937 rng(1);
    for (Scan& scan : session->scans) pad(scan.cloud, points_per_scan, rng);
    report(*session, static_cast<std::size_t>(config.flip_after / 2));
    report(*session, static_cast<std::size_t>(config.flip_after));
    report(*session, session->scans.size());
    return 0;
}
