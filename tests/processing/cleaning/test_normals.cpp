// Normal estimation and orientation against analytic shapes (sphere, plane, folded sheet).

#include <gtest/gtest.h>
#include <tbb/global_control.h>

#include <cmath>
#include <numbers>
#include <random>

#include "anascan/processing/cleaning/normals.hpp"

namespace anascan {
namespace {

constexpr float kDegree = std::numbers::pi_v<float> / 180.0f;

// Fibonacci points on a sphere of radius r (metres) centred at c.
PointCloud sphere(std::size_t n, float r, const Eigen::Vector3f& c) {
    PointCloud cloud;
    const float golden = std::numbers::pi_v<float> * (3.0f - std::sqrt(5.0f));
    for (std::size_t i = 0; i < n; ++i) {
        const float z = 1.0f - 2.0f * (float(i) + 0.5f) / float(n);
        const float rho = std::sqrt(1.0f - z * z);
        const float phi = golden * float(i);
        cloud.positions.push_back(c +
                                  r * Eigen::Vector3f(rho * std::cos(phi), rho * std::sin(phi), z));
    }
    return cloud;
}

// Randomly ordered grid points of the plane z = 0 with a little jitter in x, y.
PointCloud plane(int side, float spacing_m, std::uint64_t seed) {
    std::mt19937_64 rng(seed);
    std::uniform_real_distribution<float> jitter(-0.3f * spacing_m, 0.3f * spacing_m);
    PointCloud cloud;
    for (int i = 0; i < side; ++i) {
        for (int j = 0; j < side; ++j) {
            cloud.positions.emplace_back(float(i) * spacing_m + jitter(rng),
                                         float(j) * spacing_m + jitter(rng), 0.0f);
        }
    }
    return cloud;
}

// A sheet folded into a U: two flat arms (x in [0, 0.1], z = ±0.03) joined by a half
// cylinder of radius 0.03 m around the y axis at x = 0. Returns the outward normals too.
PointCloud folded_sheet(std::vector<Eigen::Vector3f>& outward) {
    PointCloud cloud;
    const float r = 0.03f, step = 0.002f;
    auto add = [&](const Eigen::Vector3f& p, const Eigen::Vector3f& n) {
        cloud.positions.push_back(p);
        outward.push_back(n);
    };
    for (float y = 0.0f; y <= 0.06f; y += step) {
        for (float x = 0.0f; x <= 0.1f; x += step) {
            add({x, y, r}, Eigen::Vector3f::UnitZ());
            add({x, y, -r}, -Eigen::Vector3f::UnitZ());
        }
        for (float a = step / r; a < std::numbers::pi_v<float>; a += step / r) {
            const Eigen::Vector3f n(-std::sin(a), 0.0f, std::cos(a));
            add(Eigen::Vector3f(0.0f, y, 0.0f) + r * n, n);
        }
    }
    return cloud;
}

float angle_rad(const Eigen::Vector3f& a, const Eigen::Vector3f& b) {
    return std::acos(std::clamp(a.normalized().dot(b.normalized()), -1.0f, 1.0f));
}

TEST(Normals, SphereNormalsAreRadialAndFaceAnOutsideSensor) {
    const Eigen::Vector3f centre(0.2f, -0.1f, 0.5f);
    PointCloud cloud = sphere(20000, 0.1f, centre);
    const NormalEstimationResult result = estimate_normals(cloud, {});
    EXPECT_EQ(result.status, NormalStatus::kOk);
    EXPECT_EQ(result.num_estimated, cloud.size());
    // A sensor far outside: only the visible cap can face it outward.
    const Eigen::Vector3f sensor = centre + Eigen::Vector3f(0.0f, 0.0f, 5.0f);
    orient_toward(cloud, sensor);
    for (std::size_t i = 0; i < cloud.size(); ++i) {
        const Eigen::Vector3f radial = cloud.positions[i] - centre;
        EXPECT_LT(
            std::min(angle_rad(cloud.normals[i], radial), angle_rad(cloud.normals[i], -radial)),
            1.0f * kDegree);
        EXPECT_GE(cloud.normals[i].dot(sensor - cloud.positions[i]), 0.0f);
        if (radial.z() > 0.05f) {
            EXPECT_GT(cloud.normals[i].dot(radial), 0.0f) << i;
        }
        EXPECT_NEAR(result.curvature[i], 0.0f, 0.01f);
    }
}

TEST(Normals, PlaneNormalsAreVertical) {
    PointCloud cloud = plane(100, 0.001f, 7);
    const NormalEstimationResult result = estimate_normals(cloud, {});
    EXPECT_EQ(result.num_estimated, cloud.size());
    orient_toward(cloud, Eigen::Vector3f(0.05f, 0.05f, 1.0f));
    for (std::size_t i = 0; i < cloud.size(); ++i) {
        EXPECT_LT(angle_rad(cloud.normals[i], Eigen::Vector3f::UnitZ()), 0.01f * kDegree);
        EXPECT_LT(result.curvature[i], 1e-6f);
    }
}

TEST(Normals, ConsistentOrientationOnAClosedSphereIsOutward) {
    const Eigen::Vector3f centre(1.0f, 2.0f, 3.0f);
    PointCloud cloud = sphere(10000, 0.05f, centre);
    NormalEstimationResult result = estimate_normals(cloud, {.keep_graph = true});
    const OrientationResult oriented = orient_consistently(cloud, result.graph);
    EXPECT_EQ(oriented.num_components, 1u);
    for (std::size_t i = 0; i < cloud.size(); ++i) {
        ASSERT_GT(cloud.normals[i].dot(cloud.positions[i] - centre), 0.0f) << i;
    }
}

TEST(Normals, ConsistentOrientationOnAFoldedSheetAgreesEverywhere) {
    std::vector<Eigen::Vector3f> outward;
    PointCloud cloud = folded_sheet(outward);
    estimate_normals(cloud, {.k_neighbors = 12});
    orient_consistently(cloud, ConsistentOrientationConfig{.k_neighbors = 12});
    std::size_t agree = 0;
    for (std::size_t i = 0; i < cloud.size(); ++i) agree += cloud.normals[i].dot(outward[i]) > 0.0f;
    EXPECT_TRUE(agree == cloud.size() || agree == 0) << agree << " of " << cloud.size();
}

TEST(Normals, SeveralComponentsAreEachOriented) {
    PointCloud cloud = sphere(3000, 0.05f, Eigen::Vector3f::Zero());
    append(cloud, sphere(3000, 0.05f, Eigen::Vector3f(1.0f, 0.0f, 0.0f)));
    NormalEstimationResult result = estimate_normals(cloud, {.keep_graph = true});
    const OrientationResult oriented = orient_consistently(cloud, result.graph);
    EXPECT_EQ(oriented.num_components, 2u);
    for (std::size_t i = 0; i < cloud.size(); ++i) {
        const Eigen::Vector3f centre(i < 3000 ? 0.0f : 1.0f, 0.0f, 0.0f);
        ASSERT_GT(cloud.normals[i].dot(cloud.positions[i] - centre), 0.0f) << i;
    }
}

TEST(Normals, IsolatedAndNonFinitePointsGetZeroNormalsAndAreCounted) {
    PointCloud cloud = plane(20, 0.001f, 3);
    cloud.positions.emplace_back(5.0f, 5.0f, 5.0f);  // Isolated, beyond the radius.
    cloud.positions.emplace_back(NAN, 0.0f, 0.0f);
    cloud.positions.emplace_back(0.0f, INFINITY, 0.0f);
    const NormalEstimationResult result =
        estimate_normals(cloud, {.k_neighbors = 8, .max_radius_m = 0.01f, .keep_graph = true});
    EXPECT_EQ(result.num_too_few_neighbors, 3u);
    EXPECT_EQ(result.num_estimated, 400u);
    for (std::size_t i = 0; i < cloud.size(); ++i) {
        ASSERT_TRUE(cloud.normals[i].allFinite()) << i;
        ASSERT_TRUE(std::isfinite(result.curvature[i])) << i;
    }
    EXPECT_TRUE(cloud.normals[400].isZero());
    EXPECT_EQ(orient_consistently(cloud, result.graph).num_unoriented, 3u);
    EXPECT_EQ(orient_toward(cloud, Eigen::Vector3f::UnitZ()).num_unoriented, 3u);
}

TEST(Normals, DegenerateInputsReportInsteadOfFailing) {
    PointCloud empty;
    EXPECT_EQ(estimate_normals(empty, {}).status, NormalStatus::kEmptyCloud);
    PointCloud same;
    same.positions.assign(10, Eigen::Vector3f(1.0f, 2.0f, 3.0f));
    const NormalEstimationResult result = estimate_normals(same, {});
    EXPECT_EQ(result.num_degenerate, 10u);
    for (const Eigen::Vector3f& n : same.normals) EXPECT_TRUE(n.isZero());
    PointCloud line;
    for (int i = 0; i < 10; ++i) line.positions.emplace_back(float(i), 0.0f, 0.0f);
    estimate_normals(line, {});
    for (const Eigen::Vector3f& n : line.normals) ASSERT_TRUE(n.allFinite());
}

TEST(Normals, FittingRowsAsFoundEqualsFittingTheKeptGraph) {
    PointCloud streamed = sphere(20000, 0.1f, Eigen::Vector3f::Zero());
    streamed.positions[17] = Eigen::Vector3f(NAN, 0.0f, 0.0f);
    PointCloud kept = streamed;
    const NormalEstimationResult a = estimate_normals(streamed, {});
    const NormalEstimationResult b = estimate_normals(kept, {.keep_graph = true});
    EXPECT_EQ(a.graph.size(), 0u);
    EXPECT_EQ(b.graph.size(), kept.size());
    EXPECT_EQ(streamed.normals, kept.normals);
    EXPECT_EQ(a.curvature, b.curvature);
    EXPECT_EQ(a.num_estimated, b.num_estimated);
    EXPECT_EQ(a.num_too_few_neighbors, 1u);
    EXPECT_EQ(b.num_too_few_neighbors, 1u);
}

TEST(Normals, ConsistentOrientationBuildsTheGraphWhenNoneWasKept) {
    const Eigen::Vector3f centre(1.0f, 2.0f, 3.0f);
    PointCloud cloud = sphere(5000, 0.05f, centre);
    const NormalEstimationResult result = estimate_normals(cloud, {});
    EXPECT_EQ(orient_consistently(cloud, result.graph).num_components, 1u);
    for (std::size_t i = 0; i < cloud.size(); ++i) {
        ASSERT_GT(cloud.normals[i].dot(cloud.positions[i] - centre), 0.0f) << i;
    }
}

TEST(Normals, ExistingNormalsKeepTheirSide) {
    PointCloud cloud = plane(30, 0.001f, 5);
    cloud.normals.assign(cloud.size(), -Eigen::Vector3f::UnitZ());
    estimate_normals(cloud, {});
    for (const Eigen::Vector3f& n : cloud.normals) ASSERT_LT(n.z(), -0.999f);
}

TEST(Normals, ResultDoesNotDependOnThreadCount) {
    auto run = [](int threads) {
        tbb::global_control limit(tbb::global_control::max_allowed_parallelism, threads);
        PointCloud cloud = sphere(20000, 0.1f, Eigen::Vector3f::Zero());
        NormalEstimationResult result = estimate_normals(cloud, {.keep_graph = true});
        orient_consistently(cloud, result.graph);
        return std::make_pair(cloud.normals, result.curvature);
    };
    const auto one = run(1);
    const auto two = run(2);
    EXPECT_EQ(one.first, two.first);
    EXPECT_EQ(one.second, two.second);
}

}  // namespace
}  // namespace anascan
