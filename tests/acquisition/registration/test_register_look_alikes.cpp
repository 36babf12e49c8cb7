// register_scans (the offline engine of `anascan register`) on a ray-cast session of the
// small block turned over halfway: a box whose faces look alike, so some pairs of scans fit
// at a wrong pose nearly as well as at the right one. Scans that cannot be placed are
// reported and left out, never placed wrongly without a warning. Every scan placed
// without a warning must be near its true pose. The tour has 12 views per side (30° apart,
// as `anascan capture`'s); the test takes the first ANASCAN_LOOK_ALIKE_VIEWS (default 4)
// of each side.
#include <gtest/gtest.h>

#include <algorithm>
#include <cstdio>
#include <cstdlib>
#include <string>

#include "anascan/processing/evaluation/free_space.hpp"
#include "anascan/processing/registration/batch/scan_registration.hpp"
#include "anascan/processing/registration/global/global_registration.hpp"
#include "live_session_sim.hpp"

namespace anascan {
namespace {

using anascan::testing::PlannedView;

using TrueScan = anascan::testing::RenderedScan;

constexpr int kViewsPerSide = 12;

std::vector<PlannedView> session_plan(const sim::BlockPlacement& first) {
    const std::vector<PlannedView> tour = anascan::testing::plan_tour(kViewsPerSide, first, 5);
    const char* text = std::getenv("ANASCAN_LOOK_ALIKE_VIEWS");
    const int views = std::clamp(text ? std::atoi(text) : 4, 2, kViewsPerSide);
    std::vector<PlannedView> plan;
    for (int side = 0; side < 2; ++side) {
        plan.insert(plan.end(), tour.begin() + side * kViewsPerSide,
                    tour.begin() + side * kViewsPerSide + views);
    }
    return plan;
}

std::vector<TrueScan> capture_session() {
    return anascan::testing::render_tour(
        session_plan(sim::named_scene("small-block").value().placement));
}

// The session's scans as inputs of register_scans (sensor at each scan frame's origin).
std::vector<ScanInput> session_inputs(const std::vector<TrueScan>& scans, bool origin_known) {
    std::vector<ScanInput> inputs;
    for (std::size_t i = 0; i < scans.size(); ++i) {
        inputs.push_back({.name = "scan " + std::to_string(i + 1),
                          .load = [&scans, i]() -> Expected<PointCloud> { return scans[i].cloud; },
                          .sensor_origin_scan_m = Eigen::Vector3d::Zero(),
                          .sensor_origin_known = origin_known});
    }
    return inputs;
}

// Registers the session (sensor origins known unless ANASCAN_LOOK_ALIKE_NO_FREE_SPACE is
// set; slide probes off when ANASCAN_LOOK_ALIKE_NO_SLIDE_PROBES is set), prints what each
// refined pair and each scan gave and flags every scan placed wrongly without a warning.
// Returns the number of scans placed near the truth.
std::size_t register_and_check(const std::vector<TrueScan>& scans) {
    const bool known = std::getenv("ANASCAN_LOOK_ALIKE_NO_FREE_SPACE") == nullptr;
    const std::vector<ScanInput> inputs = session_inputs(scans, known);
    ScanRegistrationConfig config;
    if (std::getenv("ANASCAN_LOOK_ALIKE_NO_SLIDE_PROBES")) {
        config.global.slide_probe_max_eigenvalue_ratio = 0.0;
    }
    const ScanRegistrationResult result = register_scans(inputs, config, {});
    for (const PairOutcome& p : result.pairs) {  // What each refined pair gave.
        if (!p.global.refined || p.global.status == GlobalRegistrationStatus::kFailedVerification)
            continue;
        const Pose T_true = scans[p.target].T_true.inverse() * scans[p.source].T_true;
        const PoseDifference d = pose_difference(p.T_target_source, T_true);
        std::printf(
            "pair %zu-%zu: %s%s, rms %.3f mm, overlap %.2f, %.1f deg %.1f mm from the truth%s, "
            "%zu poses rejected by free space, %zu slide probes\n",
            p.source + 1, p.target + 1, std::string(to_string(p.global.status)).c_str(),
            p.above_rms_gate ? " (above the gate)" : "", p.global.rms_m * 1e3,
            p.global.overlap_fraction, d.rotation_deg, d.translation_m * 1e3,
            p.in_tree ? ", tree" : "", p.free_space_rejections, p.slides.probes);
    }
    const std::size_t ref = result.reference_scan;
    std::size_t wrong = 0, near = 0;
    for (std::size_t i = 0; i < scans.size(); ++i) {
        const ScanOutcome& s = result.scans[i];
        if (!s.placed) {
            std::printf("%s: not placed: %s\n", s.name.c_str(), s.reason.c_str());
            continue;
        }
        const auto error =
            anascan::testing::pose_error(s.T_world_scan, scans[ref].T_true, scans[i].T_true,
                                         anascan::testing::centroid_of(scans[i].cloud));
        const bool ok = error.rotation_deg < 2.0 && error.translation_m < 0.005;
        std::printf("%s: placed, %.3f deg, %.3f mm%s%s\n", s.name.c_str(), error.rotation_deg,
                    error.translation_m * 1e3,
                    s.warning.empty() ? "" : ", warning: ", s.warning.c_str());
        near += ok;
        if (!ok && s.warning.empty()) {
            ++wrong;
            ADD_FAILURE() << s.name << " placed " << error.rotation_deg << " deg, "
                          << error.translation_m * 1e3 << " mm from the truth without a warning";
        }
    }
    std::printf("placed %zu of %zu (%zu groups), %zu near the truth, %zu wrong without warning\n",
                result.placed_count, scans.size(), result.group_count, near, wrong);
    return near;
}

// No scan placed wrongly without a warning. History (docs/scan-registration.md
// "Look-alike poses", "Free-space check", "Slides"): without the free-space check
// (ANASCAN_LOOK_ALIKE_NO_FREE_SPACE=1) 7 of 8 scans are placed 90° or 180° off (every verified
// pair is a look-alike at a uniform 0.8-1.0 mm RMS); with it and without the slide probes
// (ANASCAN_LOOK_ALIKE_NO_SLIDE_PROBES=1) scan 4 is placed 28 mm slid along the block at 0.02°
// (its pair with scan 2 verified there: the block's end face lay beyond the correspondence
// gate). The two sides still end in groups of 3 (see the disabled test below), so at least
// the largest group's 3 scans must be placed near the truth (leaving everything out would
// pass the check above).
TEST(RegisterLookAlikes, NoScanIsPlacedWronglyWithoutAWarning) {
    EXPECT_GE(register_and_check(capture_session()), 3u);
}

// DISABLED: fails, 3 of 8 near the truth. Each side's true neighbour pairs verify only in
// part (side B: scan 5's true pair with 6 is the 6th hypothesis and is not refined; scan 1
// verifies with none), so the session ends in groups of 3 and only the largest is placed.
TEST(RegisterLookAlikes, DISABLED_AtLeastHalfTheScansArePlacedNearTheTruth) {
    const std::vector<TrueScan> scans = capture_session();
    EXPECT_GE(register_and_check(scans), scans.size() / 2);
}

// Diagnosis (not run by default: ~1 min): every pair of the session registered on its own
// with the free-space check reporting only; prints each refined hypothesis's angle from the
// truth, RMS and free-space violation fraction.
TEST(RegisterLookAlikes, DISABLED_FreeSpaceFractionsOfEveryPair) {
    std::vector<TrueScan> scans = capture_session();
    for (TrueScan& scan : scans) prepare_scan(scan.cloud, Eigen::Vector3d::Zero(), {});
    GlobalRegistrationConfig config;
    config.free_space.max_violation_fraction = 1.0;
    const Viewpoints at_origin{.source_m = Eigen::Vector3d::Zero(),
                               .target_m = Eigen::Vector3d::Zero()};
    const char* only = std::getenv("ANASCAN_LOOK_ALIKE_PAIR");  // e.g. "4-2"
    for (std::size_t s = 1; s < scans.size(); ++s) {
        for (std::size_t t = 0; t < s; ++t) {
            if (only && std::to_string(s + 1) + "-" + std::to_string(t + 1) != only) continue;
            const GlobalRegistrationResult g =
                register_global(scans[s].cloud, scans[t].cloud, config, at_origin);
            const Pose T_true = scans[t].T_true.inverse() * scans[s].T_true;
            for (const HypothesisOutcome& h : g.hypotheses) {
                const PoseDifference d = pose_difference(h.fine.T_target_source, T_true);
                std::printf(
                    "pair %zu-%zu: %6.1f deg %7.1f mm, rms %.3f mm, overlap %.2f, "
                    "free space %.3f, ratio %.1e, %d it %s, %s%s\n",
                    s + 1, t + 1, d.rotation_deg, d.translation_m * 1e3, h.fine.rms_m * 1e3,
                    h.fine.overlap_fraction, h.free_space_violation_fraction.value_or(-1.0),
                    h.fine.degeneracy.eigenvalue_ratio, h.fine.iterations,
                    std::string(to_string(h.fine.status)).c_str(),
                    h.verified ? "verified" : h.rejection.c_str(),
                    h.slide_start_mm
                        ? (", slide probe " + std::to_string(*h.slide_start_mm) + " mm").c_str()
                        : "");
            }
        }
    }
}

// Diagnosis of the scans placed wrongly (not run by default): for each pair of such a scan
// that gave a link or a tree edge, the fine registration from its final relative pose and
// from the true one: RMS, overlap, normal deviation, degeneracy (eigenvalue ratio of the
// 6x6 system, weakest direction) and free-space fraction, and how much of the pose error
// lies along the weakest direction.
void print_fine(const char* what, const FineRegistrationResult& f, const TrueScan& s,
                const TrueScan& t, const Eigen::Vector3d& viewpoint_m) {
    const FreeSpaceConfig fs{};
    const FreeSpaceResult a =
        check_free_space(t.cloud, viewpoint_m, 0.0, s.cloud, f.T_target_source, fs);
    const FreeSpaceResult b =
        check_free_space(s.cloud, viewpoint_m, 0.0, t.cloud, f.T_target_source.inverse(), fs);
    const Eigen::Matrix<double, 6, 1>& w = f.degeneracy.weakest_direction;
    std::printf(
        "  %s: %s, %d it, rms %.3f mm, overlap %.2f, normals %.1f deg, ratio %.2e, weakest "
        "(rot %.2f %.2f %.2f, tr %.2f %.2f %.2f), free space %.3f / %.3f\n",
        what, std::string(to_string(f.status)).c_str(), f.iterations, f.rms_m * 1e3,
        f.overlap_fraction, f.normal_deviation_deg.value_or(-1.0), f.degeneracy.eigenvalue_ratio,
        w(0), w(1), w(2), w(3), w(4), w(5), a.violation_fraction, b.violation_fraction);
}

TEST(RegisterLookAlikes, DISABLED_DiagnoseWronglyPlacedScans) {
    std::vector<TrueScan> scans = capture_session();
    const std::vector<ScanInput> inputs = session_inputs(scans, true);
    const ScanRegistrationConfig config;
    const ScanRegistrationResult result = register_scans(inputs, config, {});
    for (TrueScan& scan : scans) prepare_scan(scan.cloud, Eigen::Vector3d::Zero(), config);
    const std::size_t ref = result.reference_scan;
    for (std::size_t i = 0; i < scans.size(); ++i) {
        const ScanOutcome& si = result.scans[i];
        if (!si.placed) continue;
        const auto e =
            anascan::testing::pose_error(si.T_world_scan, scans[ref].T_true, scans[i].T_true,
                                         anascan::testing::centroid_of(scans[i].cloud));
        std::printf("scan %zu: %.3f deg, %.3f mm%s\n", i + 1, e.rotation_deg, e.translation_m * 1e3,
                    si.warning.empty() ? "" : " (warning)");
        for (const PairOutcome& p : result.pairs) {
            if ((p.source != i && p.target != i) || !(p.linked || p.in_tree)) continue;
            const TrueScan& s = scans[p.source];
            const TrueScan& t = scans[p.target];
            const Pose T_final =
                result.scans[p.target].T_world_scan.inverse() * result.scans[p.source].T_world_scan;
            const Pose T_true = t.T_true.inverse() * s.T_true;
            const PoseDifference d = pose_difference(T_final, T_true);
            // The error's translation at the source centroid, in the target frame.
            const Eigen::Vector3d c = anascan::testing::centroid_of(s.cloud);
            const Eigen::Vector3d slide = T_final * c - T_true * c;
            std::printf(
                " pair %zu-%zu (%s%s%s): final %.3f deg %.1f mm from the truth, slide (%.1f %.1f "
                "%.1f) mm\n",
                p.source + 1, p.target + 1, p.in_tree ? "tree " : "", p.linked ? "link" : "",
                p.link_dropped ? " dropped" : "", d.rotation_deg, d.translation_m * 1e3,
                slide.x() * 1e3, slide.y() * 1e3, slide.z() * 1e3);
            print_fine("from final", register_fine(s.cloud, t.cloud, T_final, config.fine), s, t,
                       Eigen::Vector3d::Zero());
            print_fine("from truth", register_fine(s.cloud, t.cloud, T_true, config.fine), s, t,
                       Eigen::Vector3d::Zero());
            print_fine("global cfg", register_fine(s.cloud, t.cloud, T_final, config.global.fine),
                       s, t, Eigen::Vector3d::Zero());
        }
    }
}

}  // namespace
}  // namespace anascan
