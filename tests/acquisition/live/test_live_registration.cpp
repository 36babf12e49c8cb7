// LiveRegistrar on a ray-cast session of the small block (turned over halfway), integration
// label (a minute or more); the quick unit part (bad input, a short walk, an unrelated
// object) is test_live_registration_quick.cpp. Poses are checked against the truth in the
// block frame of the first placement.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <map>
#include <memory>

#include "anascan/acquisition/live/live_registration.hpp"
#include "live_session_sim.hpp"

namespace anascan::acquisition {
namespace {

using anascan::testing::PlannedView;

constexpr int kViewsPerSide = 12;

using CapturedScan = anascan::testing::RenderedScan;
using anascan::testing::small_block_scene;

/// The session's scans, rendered once per suite.
std::vector<CapturedScan> capture_session() {
    const sim::BlockPlacement first = sim::named_scene("small-block").value().placement;
    return anascan::testing::render_tour(anascan::testing::plan_tour(kViewsPerSide, first, 7));
}

class LiveRegistrationSession : public ::testing::Test {
protected:
    static void SetUpTestSuite() {
        scans_ = new std::vector<CapturedScan>(capture_session());
        registrar_ = new LiveRegistrar();
        decisions_ = new std::vector<LiveDecision>();
        for (std::size_t i = 0; i < scans_->size(); ++i) {
            const CapturedScan& scan = (*scans_)[i];
            decisions_->push_back(registrar_->add({.seq = static_cast<std::int64_t>(i + 1),
                                                   .cloud = scan.cloud,
                                                   .turned_over_before = scan.turned_over_before}));
            registrar_->refine();
        }
        for (int round = 0; round < 30 && registrar_->group_count() > 1; ++round) {
            registrar_->refine();
        }
        for (int round = 0; round < 3; ++round) registrar_->refine();
    }
    static void TearDownTestSuite() {
        delete decisions_;
        delete registrar_;
        delete scans_;
    }

    static inline std::vector<CapturedScan>* scans_ = nullptr;
    static inline LiveRegistrar* registrar_ = nullptr;
    static inline std::vector<LiveDecision>* decisions_ = nullptr;
};

// The consistency check's relief test (on in the live session, calibrated on the simulated
// head) takes one correct scan of this tour out as contradicting: a false alarm, which is
// flagged, never a scan left wrong. At most one such scan is allowed here.
constexpr std::size_t kMaxFalseAlarms = 1;

TEST_F(LiveRegistrationSession, EveryScanEndsInOneGroup) {
    std::size_t taken_out = 0;
    for (const LiveDecision& d : *decisions_) {
        EXPECT_TRUE(d.registered) << d.message;
        const std::optional<PoseUpdate> pose = registrar_->pose(d.seq);
        if (!pose) {
            ++taken_out;
            continue;
        }
        EXPECT_EQ(pose->group, 0) << d.message;
    }
    EXPECT_LE(taken_out, kMaxFalseAlarms);
    EXPECT_EQ(registrar_->group_count(), 1u);
    EXPECT_EQ(registrar_->model().size(), scans_->size() - taken_out);
}

TEST_F(LiveRegistrationSession, PosesMatchTheTruthInTheFirstPlacement) {
    const Pose& T_true_first = scans_->front().T_true;
    double worst_rotation_deg = 0.0, worst_translation_m = 0.0;
    for (std::size_t i = 0; i < scans_->size(); ++i) {
        const std::optional<PoseUpdate> pose = registrar_->pose(static_cast<std::int64_t>(i + 1));
        if (!pose) continue;  // Taken out as contradicting (EveryScanEndsInOneGroup counts them).
        const anascan::testing::PoseError e =
            anascan::testing::pose_error(pose->T_group_scan, T_true_first, (*scans_)[i].T_true,
                                         anascan::testing::centroid_of((*scans_)[i].cloud));
        if (std::getenv("ANASCAN_LIVE_VERBOSE")) {
            std::printf("%s | error %.4f deg %.4f mm\n", (*decisions_)[i].message.c_str(),
                        e.rotation_deg, e.translation_m * 1e3);
            for (const LiveAttempt& a : (*decisions_)[i].attempts) {
                std::printf("    %s -> %s (target %lld, rms %.3f mm, overlap %.2f, %.3f s)\n",
                            to_string(a.method).data(), a.status.c_str(),
                            static_cast<long long>(a.target_seq), a.rms_m * 1e3, a.overlap_fraction,
                            a.time_s);
            }
        }
        worst_rotation_deg = std::max(worst_rotation_deg, e.rotation_deg);
        worst_translation_m = std::max(worst_translation_m, e.translation_m);
    }
    RecordProperty("worst_rotation_deg", std::to_string(worst_rotation_deg));
    RecordProperty("worst_translation_mm", std::to_string(worst_translation_m * 1e3));
    // Measured: 0.0035° / 0.091 mm; without the links across the turn-over (degenerate:
    // a band of the sides) 0.0063° / 0.145 mm, the second side hanging on the merge.
    EXPECT_LT(worst_rotation_deg, 0.005);
    EXPECT_LT(worst_translation_m, 0.00012);
}

TEST_F(LiveRegistrationSession, CheapHypothesesCarryTheTourAndTheFlipOpensAGroup) {
    const std::vector<LiveDecision>& d = *decisions_;
    EXPECT_EQ(d[0].method, LiveMethod::kFirst);
    std::size_t cheap = 0;
    for (std::size_t i = 1; i < d.size(); ++i) {
        cheap +=
            d[i].method == LiveMethod::kMotionPrior || d[i].method == LiveMethod::kPreviousPose;
        if (i != kViewsPerSide) {
            EXPECT_FALSE(d[i].attempts.empty()) << d[i].message;
        }
    }
    // Steps of 30° with elevations alternating by 20°: the motion priors need three placed
    // scans of a group, and the operator's jitter defeats them now and then.
    EXPECT_GE(cheap, d.size() / 2);
    // The first scan after the flip tries nothing: the stone moved, and the other side
    // matches it only by look-alike poses. It opens a group of its own, which the
    // whole-group merge joins to the first side later (EveryScanEndsInOneGroup).
    const LiveDecision& flipped = d[kViewsPerSide];
    EXPECT_TRUE(flipped.attempts.empty()) << flipped.message;
    EXPECT_EQ(flipped.method, LiveMethod::kNewGroup) << flipped.message;
}

TEST_F(LiveRegistrationSession, DecisionsCarryTheirFigures) {
    for (const LiveDecision& d : *decisions_) {
        if (d.method == LiveMethod::kFirst || d.method == LiveMethod::kNewGroup) continue;
        EXPECT_GT(d.overlap_fraction, 0.3) << d.message;
        EXPECT_GT(d.rms_m, 0.0) << d.message;
        EXPECT_LT(d.rms_m, 0.002) << d.message;
        EXPECT_GT(d.degeneracy, 0.0) << d.message;
        EXPECT_GT(d.time_s, 0.0) << d.message;
        EXPECT_EQ(d.attempts.back().status.substr(0, 8), "verified") << d.message;
    }
}

TEST_F(LiveRegistrationSession, ReducedCloudsAreStoneOnly) {
    // In the first placement's world frame the ground is z = 0 and the stone above it.
    for (const LiveModelScan& m : registrar_->model()) {
        const Pose& T_true = (*scans_)[static_cast<std::size_t>(m.seq - 1)].T_true;
        std::size_t near_ground = 0;
        const sim::BlockPlacement first = sim::named_scene("small-block").value().placement;
        const sim::Scene scene0 = sim::make_scene(small_block_scene(first));
        const Pose T_block_scan = scene0.T_world_block.inverse() * T_true;
        for (std::size_t i = 0; i < m.cloud->size(); ++i) {
            const Eigen::Vector3d p = T_block_scan * m.cloud->world_position(i);
            const Eigen::Vector3d outside =
                (p.cwiseAbs() - 0.5 * scene0.block_size_m).cwiseMax(0.0);
            near_ground += outside.norm() > 0.02;  // Farther than any relief from the block.
        }
        EXPECT_LT(near_ground, m.cloud->size() / 100 + 5) << "scan " << m.seq;
        break;  // One scan suffices (the scene is rebuilt per check).
    }
}

}  // namespace
}  // namespace anascan::acquisition
