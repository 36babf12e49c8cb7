#include <gtest/gtest.h>

#include <nlohmann/json.hpp>

#include "anascan/processing/planning/next_best_view.hpp"

namespace anascan {
namespace {

// An Octagon-sized block (1.2 x 0.6 x 0.5 m) resting on the ground z = 0, its centre over
// the origin, as a coverage report: surface samples every 2 cm on each face with outward
// normals, each face observed or not as asked.
enum Face { kPlusX, kMinusX, kPlusY, kMinusY, kTop, kBottom, kFaces };
const Eigen::Vector3d kSize(1.2, 0.6, 0.5);

Mesh box_mesh() {
    Mesh mesh;
    for (int i = 0; i < 8; ++i)
        mesh.vertices.positions.emplace_back(static_cast<float>((i & 1 ? 0.5 : -0.5) * kSize.x()),
                                             static_cast<float>((i & 2 ? 0.5 : -0.5) * kSize.y()),
                                             static_cast<float>(i & 4 ? kSize.z() : 0.0));
    mesh.triangles = {{0, 2, 1}, {1, 2, 3}, {4, 5, 6}, {5, 7, 6}, {0, 1, 4}, {1, 5, 4},
                      {2, 6, 3}, {3, 6, 7}, {0, 4, 2}, {2, 4, 6}, {1, 3, 5}, {3, 7, 5}};
    return mesh;
}

void add_face(CoverageReport& r, Face face, bool observed) {
    const double step = 0.02;
    const int axis =
        face == kTop || face == kBottom ? 2 : (face == kPlusX || face == kMinusX ? 0 : 1);
    const double sign = face == kPlusX || face == kPlusY || face == kTop ? 1.0 : -1.0;
    const int u = (axis + 1) % 3, v = (axis + 2) % 3;
    for (double a = step / 2; a < kSize[u]; a += step)
        for (double b = step / 2; b < kSize[v]; b += step) {
            Eigen::Vector3d p(-0.5 * kSize.x(), -0.5 * kSize.y(), 0.0);
            p[u] += a, p[v] += b;
            p[axis] = axis == 2 ? (sign > 0 ? kSize.z() : 0.0) : sign * 0.5 * kSize[axis];
            Eigen::Vector3f n = Eigen::Vector3f::Zero();
            n[axis] = static_cast<float>(sign);
            r.samples.positions.push_back(p.cast<float>());
            r.samples.normals.push_back(n);
            r.sample_states.push_back(observed ? SampleState::kObserved : SampleState::kUnobserved);
        }
}

CoverageReport block_coverage(const std::array<bool, kFaces>& observed, bool with_ground = true) {
    CoverageReport r;
    r.status = CoverageStatus::kOk;
    r.surface = box_mesh();
    for (int f = 0; f < kFaces; ++f) add_face(r, static_cast<Face>(f), observed[f]);
    r.surface_area_m2 =
        2.0 * (kSize.x() * kSize.y() + kSize.x() * kSize.z() + kSize.y() * kSize.z());
    std::size_t seen = 0;
    for (SampleState s : r.sample_states) seen += s == SampleState::kObserved ? 1 : 0;
    r.fraction = static_cast<double>(seen) / static_cast<double>(r.sample_states.size());
    if (with_ground) r.ground_world = Plane{.normal = Eigen::Vector3d::UnitZ(), .offset_m = 0.0};
    return r;
}

bool outside_box(const Eigen::Vector3d& p, double margin) {
    return std::abs(p.x()) > 0.5 * kSize.x() + margin ||
           std::abs(p.y()) > 0.5 * kSize.y() + margin || p.z() > kSize.z() + margin;
}

TEST(NextBestView, AimsAtTheUnseenSideFromWhereAnOperatorCanStand) {
    // Seen: +x, +y, top. Unseen: -x end (0.30 m²), -y side (0.60 m²), the bottom.
    const CoverageReport coverage = block_coverage({true, false, true, false, true, false});
    const NextView view = plan_next_view(coverage, {});
    ASSERT_EQ(view.advice, NextViewAdvice::kScan) << view.hint;
    const Eigen::Vector3d s = view.sensor_world_m;
    EXPECT_TRUE(s.x() < -0.5 * kSize.x() || s.y() < -0.5 * kSize.y()) << s.transpose();
    EXPECT_TRUE(outside_box(s, 0.25)) << s.transpose();
    EXPECT_GE(s.z(), 0.25);
    EXPECT_LE(s.z(), 1.9);
    EXPECT_NEAR(view.height_m, s.z(), 1e-9);
    // The -y side is the largest unseen face a view can reach; at 33° x 25° from at most
    // 1.6 m a view takes a good part of it, never more than what is unseen.
    EXPECT_GT(view.gain_fraction, 0.05);
    EXPECT_LE(view.gain_area_m2, 0.30 + 0.60 + 1e-6);
    EXPECT_GE(view.overlap_fraction, 0.4);  // The new scan must register to the model.
    EXPECT_NE(view.hint.find("-y"), std::string::npos) << view.hint;
    EXPECT_NE(view.hint.find("% coverage"), std::string::npos) << view.hint;
    // The face it rests on is out of any view's reach until the turn.
    EXPECT_NEAR(view.after_turn_area_m2, kSize.x() * kSize.y(), 0.05);
}

TEST(NextBestView, WalksOnFromWhereTheModelWasScanned) {
    NextViewConfig config;
    config.scanner_positions_world = {Eigen::Vector3d(1.5, 0.0, 0.8)};  // Off the +x end.
    config.max_step_deg = 40.0;
    const NextView view =
        plan_next_view(block_coverage({true, false, false, false, true, false}), config);
    ASSERT_EQ(view.advice, NextViewAdvice::kScan) << view.hint;
    const Eigen::Vector3d centre(0.0, 0.0, 0.25);
    const double step =
        std::acos((view.sensor_world_m - centre)
                      .normalized()
                      .dot((config.scanner_positions_world[0] - centre).normalized())) *
        180.0 / 3.14159265358979;
    EXPECT_LE(step, 40.0 + 1e-6);
}

TEST(NextBestView, DoesNotAskAgainForAViewWhoseScanDidNotJoin) {
    const CoverageReport coverage = block_coverage({true, false, true, false, true, false});
    const NextView first = plan_next_view(coverage, {});
    ASSERT_EQ(first.advice, NextViewAdvice::kScan) << first.hint;
    NextViewConfig config;
    config.failed_sensor_positions_world = {first.sensor_world_m};
    const NextView second = plan_next_view(coverage, config);
    ASSERT_EQ(second.advice, NextViewAdvice::kScan) << second.hint;
    EXPECT_GE((second.sensor_world_m - first.sensor_world_m).norm(), config.failed_view_radius_m);
    EXPECT_GT(second.gain_fraction, 0.0);
    EXPECT_LE(second.gain_fraction, first.gain_fraction + 1e-12);  // the best was taken away
}

TEST(NextBestView, TakesTheUpHintWithoutAGround) {
    NextViewConfig config;
    config.up_hint_world = Eigen::Vector3d(0.05, 0.0, 1.0);
    const NextView view = plan_next_view(
        block_coverage({true, false, true, false, true, false}, /*with_ground=*/false), config);
    EXPECT_GT(view.frame.R_stone_world.row(2).dot(Eigen::Vector3d::UnitZ()), 0.99);
    EXPECT_EQ(view.advice, NextViewAdvice::kScan);
}

TEST(NextBestView, SaysTurnOverWhenOnlyTheRestingFaceIsLeft) {
    const CoverageReport coverage = block_coverage({true, true, true, true, true, false});
    const NextView view = plan_next_view(coverage, {});
    EXPECT_EQ(view.advice, NextViewAdvice::kTurnOver) << view.hint;
    EXPECT_NEAR(view.after_turn_area_m2, kSize.x() * kSize.y(), 0.05);
    EXPECT_NE(view.hint.find("turn the stone over"), std::string::npos);
}

TEST(NextBestView, IsDoneWhenEverythingIsObserved) {
    const CoverageReport coverage = block_coverage({true, true, true, true, true, true});
    EXPECT_EQ(plan_next_view(coverage, {}).advice, NextViewAdvice::kDone);
}

TEST(NextBestView, KeepsTheScannerInsideTheTentAndAboveTheGround) {
    NextViewConfig config;
    config.scanner.max_radius_m = 1.2;
    config.scanner.min_height_m = 0.8;
    const NextView view =
        plan_next_view(block_coverage({false, false, false, false, true, false}), config);
    ASSERT_EQ(view.advice, NextViewAdvice::kScan) << view.hint;
    EXPECT_LE(view.sensor_world_m.head<2>().norm(), 1.2 + 1e-9);
    EXPECT_GE(view.sensor_world_m.z(), 0.8 - 1e-9);
    EXPECT_TRUE(outside_box(view.sensor_world_m, 0.25));
}

TEST(NextBestView, GuessesUpWithoutAGroundAndSaysSo) {
    const CoverageReport coverage =
        block_coverage({true, false, true, false, true, false}, /*with_ground=*/false);
    const NextView view = plan_next_view(coverage, {});
    EXPECT_FALSE(view.frame.ground_known);
    // The block's thinnest direction is z; the model frame's -y rule picks a sign.
    EXPECT_NEAR(std::abs(view.frame.R_stone_world.row(2).z()), 1.0, 1e-6);
    EXPECT_NE(view.hint.find("lowest point"), std::string::npos) << view.hint;
}

TEST(NextBestView, IsReproducibleAndWritesItsJson) {
    const CoverageReport coverage = block_coverage({true, false, false, true, true, false});
    const NextView a = plan_next_view(coverage, {}), b = plan_next_view(coverage, {});
    EXPECT_EQ(a.sensor_world_m, b.sensor_world_m);
    EXPECT_EQ(a.hint, b.hint);
    const auto j = nlohmann::json::parse(next_view_to_json(a));
    EXPECT_EQ(j.at("advice"), "scan");
    EXPECT_NEAR(j.at("gain_percent").get<double>(), 100.0 * a.gain_fraction, 1e-9);
    EXPECT_EQ(j.at("sensor_m").size(), 3u);
    EXPECT_TRUE(j.at("stone_frame").at("ground_known").get<bool>());
}

TEST(NextBestView, SaysSoWithoutACoverage) {
    CoverageReport coverage;
    coverage.status = CoverageStatus::kNoStone;
    const NextView view = plan_next_view(coverage, {});
    EXPECT_EQ(view.advice, NextViewAdvice::kNoCoverage);
    EXPECT_FALSE(view.hint.empty());
}

}  // namespace
}  // namespace anascan
