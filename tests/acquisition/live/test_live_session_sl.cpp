// LiveRegistrar on a simulated structured-light session of the small block (the real
// decoder, 135-210k points per scan): views around the block, turned over halfway, refine()
// after each scan as the registration worker does. Views: ANASCAN_LIVE_VIEWS (default 8;
// scripts/live-session-check.sh runs the 24). Prints the figures of the session.
#include <gtest/gtest.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <map>
#include <string>

#include "anascan/acquisition/live/live_registration.hpp"
#include "anascan/processing/core/stopwatch.hpp"
#include "anascan/processing/spatial/kdtree.hpp"
#include "anascan/sim/sim_structured_light_scanner.hpp"
#include "live_session_sim.hpp"

namespace anascan::acquisition {
namespace {

/// The tour has 12 views per side (30° steps). ANASCAN_LIVE_VIEWS=N takes the first N/2 of
/// each side (the figure is N = 24, turned over after 12); without it the test
/// registers the first 8 views of the first side (a minute or two with the real decoder).
constexpr int kViewsPerSide = 12;

std::vector<anascan::testing::PlannedView> session_plan(const sim::BlockPlacement& placement) {
    const std::vector<anascan::testing::PlannedView> tour =
        anascan::testing::plan_tour(kViewsPerSide, placement, 11);
    const char* text = std::getenv("ANASCAN_LIVE_VIEWS");
    if (!text) return {tour.begin(), tour.begin() + 8};
    const int half = std::clamp(std::atoi(text) / 2, 2, kViewsPerSide);
    std::vector<anascan::testing::PlannedView> plan;
    for (int side = 0; side < 2; ++side) {
        plan.insert(plan.end(), tour.begin() + side * kViewsPerSide,
                    tour.begin() + side * kViewsPerSide + half);
    }
    return plan;
}

double percentile(std::vector<double> values, double q) {
    std::sort(values.begin(), values.end());
    const std::size_t k =
        static_cast<std::size_t>(q * static_cast<double>(values.size() - 1) + 0.5);
    return values[k];
}

/// Median distance (mm) from the points of `a` to their nearest point of `b` (both placed by
/// their poses), over the pairs closer than 20 mm.
double median_gap_mm(const LiveModelScan& a, const Pose& T_a, const LiveModelScan& b,
                     const Pose& T_b) {
    const PointCloud target = transformed(*b.cloud, T_b);
    const PointCloud source = transformed(*a.cloud, T_a);
    const KdTree tree(target.positions);
    std::vector<double> gaps;
    Neighbor n;
    for (std::size_t i = 0; i < source.size(); i += 10) {
        const Eigen::Vector3f q = (source.world_position(i) - target.origin_m).cast<float>();
        if (tree.nearest(q, n) && n.distance_sq_m2 < 4e-4f)
            gaps.push_back(std::sqrt(n.distance_sq_m2));
    }
    if (gaps.empty()) return -1.0;
    std::nth_element(gaps.begin(), gaps.begin() + gaps.size() / 2, gaps.end());
    return gaps[gaps.size() / 2] * 1e3;
}

/// Whether consecutive scans fit each other under the simulated truth and under the
/// registered poses: tells a registration error from an inconsistent simulated truth.
void print_consecutive_gaps(const LiveRegistrar& registrar, const std::vector<Pose>& truth) {
    const std::vector<LiveModelScan> model = registrar.model();
    for (std::size_t k = 1; k < model.size(); ++k) {
        const std::size_t a = static_cast<std::size_t>(model[k].seq - 1);
        const std::size_t b = static_cast<std::size_t>(model[k - 1].seq - 1);
        const Pose T_a = truth.front().inverse() * truth[a];
        const Pose T_b = truth.front().inverse() * truth[b];
        std::printf("gap scan %zu to %zu: truth %.3f mm, registered %.3f mm\n", a + 1, b + 1,
                    median_gap_mm(model[k], T_a, model[k - 1], T_b),
                    median_gap_mm(model[k], model[k].T_group_scan, model[k - 1],
                                  model[k - 1].T_group_scan));
    }
}

// What the walk registered live: the truth and centroid of every scan, the time of each
// add() and how each scan was placed.
struct Walk {
    std::vector<double> add_s;
    std::vector<Pose> truth;
    std::vector<Eigen::Vector3d> centroids;
    std::map<std::string, int> methods;
};

void print_attempts(const LiveDecision& d) {
    if (!std::getenv("ANASCAN_LIVE_VERBOSE")) return;
    for (const LiveAttempt& a : d.attempts) {
        std::printf("    %s -> %s (target %lld, rms %.3f mm, overlap %.2f, %.3f s)\n",
                    to_string(a.method).data(), a.status.c_str(),
                    static_cast<long long>(a.target_seq), a.rms_m * 1e3, a.overlap_fraction,
                    a.time_s);
    }
}

void refine_once(LiveRegistrar& registrar) {
    const Stopwatch watch;
    const std::size_t changed = registrar.refine().size();
    std::printf("    refine: %zu poses changed, %zu new links, %zu merges, %.3f s\n", changed,
                registrar.last_refine_report().new_links, registrar.last_refine_report().merges,
                watch.seconds());
}

// Captures and registers every planned view, refining after each as the worker does.
void register_walk(const sim::SceneConfig& scene,
                   const std::vector<anascan::testing::PlannedView>& plan, LiveRegistrar& registrar,
                   Walk& walk) {
    auto device = sim::SimStructuredLightScanner::open({.scene = scene, .advance_deg = 0.0});
    const Pose T_world_block0 = sim::block_pose(scene.placement, scene.block.size_m);
    for (std::size_t i = 0; i < plan.size(); ++i) {
        device->place_block(plan[i].placement);
        device->move_to(plan[i].view);
        Expected<Scan> scan = device->capture_scan({});
        ASSERT_TRUE(scan.has_value()) << scan.error().message;
        walk.truth.push_back(anascan::testing::true_pose_in_first_placement(
            T_world_block0, sim::block_pose(plan[i].placement, scene.block.size_m),
            *scan->meta.T_world_scan));
        walk.centroids.push_back(anascan::testing::centroid_of(scan->cloud));
        const std::size_t points = scan->cloud.size();
        const LiveDecision d =
            registrar.add({.seq = static_cast<std::int64_t>(i + 1),
                           .cloud = std::move(scan->cloud),
                           .sensor_origin_scan_m = scan->meta.sensor_origin_scan_m,
                           .turned_over_before = plan[i].turned_over_before});
        walk.add_s.push_back(d.time_s);
        ++walk.methods[std::string(to_string(d.method))];
        std::printf("%zu points | %s\n", points, d.message.c_str());
        print_attempts(d);
        std::fflush(stdout);
        refine_once(registrar);
    }
}

struct WorstError {
    double rotation_deg = 0.0, translation_m = 0.0;
};

// Every scan in group 0, and the worst error against the truth (printed per scan, with the
// error in the scan's own frame: along its optical axis z, a depth bias of the scan itself).
void check_poses(const LiveRegistrar& registrar, const Walk& walk, WorstError& worst) {
    for (std::size_t i = 0; i < walk.truth.size(); ++i) {
        const std::optional<PoseUpdate> pose = registrar.pose(static_cast<std::int64_t>(i + 1));
        ASSERT_TRUE(pose.has_value()) << "scan " << i + 1;
        EXPECT_EQ(pose->group, 0) << "scan " << i + 1;
        const Eigen::Vector3d& c = walk.centroids[i];
        const anascan::testing::PoseError e =
            anascan::testing::pose_error(pose->T_group_scan, walk.truth.front(), walk.truth[i], c);
        const Pose T_first_scan_true = walk.truth.front().inverse() * walk.truth[i];
        const Eigen::Vector3d error_scan_m =
            T_first_scan_true.inverse() * (pose->T_group_scan * c) - c;
        const Eigen::Vector3d error_first_m = pose->T_group_scan * c - T_first_scan_true * c;
        std::printf(
            "scan %zu: group %d, error %.4f deg, %.4f mm (scan frame %.2f %.2f %.2f mm, first "
            "scan's frame %.2f %.2f %.2f mm)\n",
            i + 1, pose->group, e.rotation_deg, e.translation_m * 1e3, error_scan_m.x() * 1e3,
            error_scan_m.y() * 1e3, error_scan_m.z() * 1e3, error_first_m.x() * 1e3,
            error_first_m.y() * 1e3, error_first_m.z() * 1e3);
        worst.rotation_deg = std::max(worst.rotation_deg, e.rotation_deg);
        worst.translation_m = std::max(worst.translation_m, e.translation_m);
    }
}

TEST(LiveSessionStructuredLight, EveryScanRegisteredInOneGroupNearTheTruth) {
    const sim::SceneConfig scene = sim::named_scene("small-block").value();
    const std::vector<anascan::testing::PlannedView> plan = session_plan(scene.placement);
    LiveRegistrar registrar;
    Walk walk;
    register_walk(scene, plan, registrar, walk);
    if (HasFatalFailure()) return;
    // The worker refines while idle: until the groups merged, then a few more rounds.
    for (int round = 0; round < 30 && registrar.group_count() > 1; ++round) registrar.refine();
    for (int round = 0; round < 3; ++round) registrar.refine();
    WorstError worst;
    check_poses(registrar, walk, worst);
    if (std::getenv("ANASCAN_LIVE_VERBOSE")) print_consecutive_gaps(registrar, walk.truth);
    std::printf(
        "views %zu, groups %zu, max rotation error %.4f deg, max translation error %.4f mm\n",
        plan.size(), registrar.group_count(), worst.rotation_deg, worst.translation_m * 1e3);
    std::printf(
        "add() median %.3f s, p95 %.3f s, max %.3f s; methods:", percentile(walk.add_s, 0.5),
        percentile(walk.add_s, 0.95), percentile(walk.add_s, 1.0));
    for (const auto& [method, count] : walk.methods) std::printf(" %s %d", method.c_str(), count);
    std::printf("\n");
    EXPECT_EQ(registrar.group_count(), 1u);
    if (std::getenv("ANASCAN_LIVE_VIEWS")) {
        // The goal, checked by scripts/live-session-check.sh (not met yet: see
        // docs/live-registration.md).
        EXPECT_LT(worst.rotation_deg, 0.05);
        EXPECT_LT(worst.translation_m, 0.0002);
    } else {
        // Every scan placed, none on a look-alike pose (90°/180° turns, slides of centimetres).
        EXPECT_LT(worst.rotation_deg, 0.5);
        EXPECT_LT(worst.translation_m, 0.02);
    }
}

}  // namespace
}  // namespace anascan::acquisition
