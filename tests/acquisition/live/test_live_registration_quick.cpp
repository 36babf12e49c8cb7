// LiveRegistrar, the quick part (unit): a short ray-cast walk of small steps around the
// small block (cheap hypotheses only), unusable scans, and a scan of an unrelated object.
// The whole turned-over session is test_live_registration.cpp (integration).
#include <gtest/gtest.h>

#include <algorithm>
#include <limits>
#include <memory>
#include <random>

#include "anascan/acquisition/live/live_registration.hpp"
#include "live_session_sim.hpp"

namespace anascan::acquisition {
namespace {

struct QuickScan {
    PointCloud cloud;
    Pose T_true = Pose::Identity();
};

/// Five views 12° apart (elevation 35°), 300×225 px: every step is a cheap hypothesis.
std::vector<QuickScan> capture_walk() {
    sim::SceneConfig config = sim::named_scene("small-block").value();
    config.block.grid_step_m = 0.003;
    config.with_tent = false;
    const sim::Scene scene = sim::make_scene(config);
    const sim::RayCaster caster = sim::RayCaster::create(scene.mesh).value();
    std::vector<QuickScan> scans;
    for (int k = 0; k < 5; ++k) {
        const sim::Viewpoint view{.azimuth_deg = 30.0 + 12.0 * k,
                                  .elevation_deg = 35.0 + (k % 2 == 0 ? 0.0 : 4.0),
                                  .distance_m = 1.1};
        const Pose T_world_sensor =
            sim::sensor_looking_at(anascan::testing::aim_point(scene), view);
        QuickScan scan;
        scan.cloud = anascan::testing::pinhole_scan(
            caster, T_world_sensor, {.width_px = 300, .height_px = 225, .focal_px = 510.0},
            static_cast<std::uint32_t>(k + 1));
        scan.T_true = T_world_sensor;
        scans.push_back(std::move(scan));
    }
    return scans;
}

/// No background features (no global registration is needed on this walk).
LiveRegistrationConfig quick_config() { return {.max_features_per_refine = 0}; }

class LiveRegistrationWalk : public ::testing::Test {
protected:
    static void SetUpTestSuite() {
        scans_ = new std::vector<QuickScan>(capture_walk());
        registrar_ = new LiveRegistrar(quick_config());
        decisions_ = new std::vector<LiveDecision>();
        for (std::size_t i = 0; i < scans_->size(); ++i) {
            decisions_->push_back(registrar_->add(
                {.seq = static_cast<std::int64_t>(i + 1), .cloud = (*scans_)[i].cloud}));
            registrar_->refine();
        }
        registrar_->refine();
    }
    static void TearDownTestSuite() {
        delete decisions_;
        delete registrar_;
        delete scans_;
    }

    static inline std::vector<QuickScan>* scans_ = nullptr;
    static inline LiveRegistrar* registrar_ = nullptr;
    static inline std::vector<LiveDecision>* decisions_ = nullptr;
};

TEST_F(LiveRegistrationWalk, SmallStepsTakeTheCheapHypotheses) {
    const std::vector<LiveDecision>& d = *decisions_;
    EXPECT_EQ(d[0].method, LiveMethod::kFirst);
    for (std::size_t i = 1; i < d.size(); ++i) {
        EXPECT_TRUE(d[i].method == LiveMethod::kMotionPrior ||
                    d[i].method == LiveMethod::kPreviousPose)
            << d[i].message;
        EXPECT_EQ(d[i].group, 0) << d[i].message;
    }
    EXPECT_EQ(registrar_->group_count(), 1u);
}

TEST_F(LiveRegistrationWalk, PosesMatchTheTruth) {
    const Pose& T_true_first = scans_->front().T_true;
    for (std::size_t i = 0; i < scans_->size(); ++i) {
        const std::optional<PoseUpdate> pose = registrar_->pose(static_cast<std::int64_t>(i + 1));
        ASSERT_TRUE(pose.has_value());
        const anascan::testing::PoseError e =
            anascan::testing::pose_error(pose->T_group_scan, T_true_first, (*scans_)[i].T_true,
                                         anascan::testing::centroid_of((*scans_)[i].cloud));
        EXPECT_LT(e.rotation_deg, 0.05) << (*decisions_)[i].message;
        EXPECT_LT(e.translation_m, 0.0002) << (*decisions_)[i].message;
    }
}

TEST_F(LiveRegistrationWalk, DecisionsCarryTheirFigures) {
    for (const LiveDecision& d : *decisions_) {
        if (d.method == LiveMethod::kFirst) continue;
        EXPECT_GT(d.overlap_fraction, 0.3) << d.message;
        EXPECT_GT(d.rms_m, 0.0) << d.message;
        EXPECT_LT(d.rms_m, 0.001) << d.message;
        EXPECT_GT(d.degeneracy, 0.0) << d.message;
        EXPECT_GT(d.time_s, 0.0) << d.message;
        ASSERT_FALSE(d.attempts.empty()) << d.message;
        EXPECT_EQ(d.attempts.back().status, "verified") << d.message;
    }
}

TEST_F(LiveRegistrationWalk, ReducedCloudsAreStoneOnly) {
    sim::SceneConfig config = sim::named_scene("small-block").value();
    config.with_tent = false;
    const sim::Scene scene = sim::make_scene(config);
    for (const LiveModelScan& m : registrar_->model()) {
        const Pose T_block_scan =
            scene.T_world_block.inverse() * (*scans_)[static_cast<std::size_t>(m.seq - 1)].T_true;
        std::size_t off_stone = 0;
        for (std::size_t i = 0; i < m.cloud->size(); ++i) {
            const Eigen::Vector3d p = T_block_scan * m.cloud->world_position(i);
            const Eigen::Vector3d outside = (p.cwiseAbs() - 0.5 * scene.block_size_m).cwiseMax(0.0);
            off_stone += outside.norm() > 0.02;  // Farther than any relief from the block.
        }
        EXPECT_LT(off_stone, m.cloud->size() / 100 + 5) << "scan " << m.seq;
    }
}

TEST_F(LiveRegistrationWalk, ExcludedScansLeaveTheModelAndComeBack) {
    LiveRegistrar& r = *registrar_;
    r.exclude(3, true);
    const std::vector<LiveModelScan> model = r.model();
    EXPECT_EQ(model.size(), scans_->size() - 1);
    EXPECT_TRUE(std::none_of(model.begin(), model.end(),
                             [](const LiveModelScan& m) { return m.seq == 3; }));
    r.exclude(3, false);
    EXPECT_EQ(r.model().size(), scans_->size());
}

TEST_F(LiveRegistrationWalk, AScanRegisteredAgainIsPlacedGloballyAndOnce) {
    // Its own registrar (with features for the global registration): the operator asks to
    // register scan 3 again; it must come back in the same group, once, at the same pose.
    LiveRegistrar r;
    for (std::size_t i = 0; i < scans_->size(); ++i)
        ASSERT_TRUE(r.add({.seq = static_cast<std::int64_t>(i + 1), .cloud = (*scans_)[i].cloud})
                        .registered);
    const LiveDecision again = r.reregister({.seq = 3, .cloud = (*scans_)[2].cloud});
    ASSERT_TRUE(again.registered) << again.message;
    EXPECT_EQ(again.method, LiveMethod::kGlobal) << again.message;
    EXPECT_EQ(again.group, 0) << again.message;
    const std::vector<LiveModelScan> model = r.model();
    EXPECT_EQ(model.size(), scans_->size());
    EXPECT_EQ(std::count_if(model.begin(), model.end(),
                            [](const LiveModelScan& m) { return m.seq == 3; }),
              1);
    const anascan::testing::PoseError e = anascan::testing::pose_error(
        again.T_group_scan, scans_->front().T_true, (*scans_)[2].T_true,
        anascan::testing::centroid_of((*scans_)[2].cloud));
    EXPECT_LT(e.rotation_deg, 0.05) << again.message;
    EXPECT_LT(e.translation_m, 0.0002) << again.message;
    r.refine();  // Links and refinement run without the retired entry.
    EXPECT_EQ(r.group_count(), 1u);
}

TEST_F(LiveRegistrationWalk, ScansAfterAGapPlaceTheScanBeforeItByTheCaptureOrder) {
    // The walk without its second view: a first step of 24°, beyond what a previous-pose
    // hypothesis may correct, and no global registration: scan 2 opens a group, scans 3-4
    // join it on the cheap hypotheses. refine() then runs the motion priors backwards from
    // scans 2-4, places scan 1 in their group and merges the groups (the merges by global
    // registration are off).
    LiveRegistrar r({.global = {.max_targets = 0},
                     .merges = {.whole_groups = false, .max_attempts = 0},
                     .max_features_per_refine = 0});
    const std::vector<std::size_t> views = {0, 2, 3, 4};
    std::vector<LiveDecision> d;
    for (std::size_t k = 0; k < views.size(); ++k)
        d.push_back(
            r.add({.seq = static_cast<std::int64_t>(k + 1), .cloud = (*scans_)[views[k]].cloud}));
    ASSERT_EQ(d[1].method, LiveMethod::kNewGroup) << d[1].message;
    EXPECT_EQ(r.group_count(), 2u);
    for (int round = 0; round < 3 && r.group_count() > 1; ++round) r.refine();
    ASSERT_EQ(r.group_count(), 1u);
    const std::optional<PoseUpdate> first = r.pose(1);
    ASSERT_TRUE(first.has_value());
    for (std::size_t k = 0; k < views.size(); ++k) {
        const std::optional<PoseUpdate> pose = r.pose(static_cast<std::int64_t>(k + 1));
        ASSERT_TRUE(pose.has_value());
        // In the frame of scan 1 (the surviving group is the lower id, scan 1's).
        const anascan::testing::PoseError e = anascan::testing::pose_error(
            first->T_group_scan.inverse() * pose->T_group_scan, (*scans_)[0].T_true,
            (*scans_)[views[k]].T_true, anascan::testing::centroid_of((*scans_)[views[k]].cloud));
        EXPECT_LT(e.rotation_deg, 0.05) << "scan " << k + 1;
        EXPECT_LT(e.translation_m, 0.0002) << "scan " << k + 1;
    }
}

TEST_F(LiveRegistrationWalk, EachScanLinksToItsBestEarlierPartnersOnly) {
    // Every pair of the walk overlaps (10 pairs); with two links per scan to earlier scans
    // the scans keep 1 + 2 + 2 + 2 links, and the refined poses stay as close to the truth.
    LiveRegistrationConfig config = quick_config();
    config.links.max_per_scan = 2;
    LiveRegistrar r(config);
    for (std::size_t i = 0; i < scans_->size(); ++i) {
        ASSERT_TRUE(r.add({.seq = static_cast<std::int64_t>(i + 1), .cloud = (*scans_)[i].cloud})
                        .registered);
        r.refine();
    }
    for (int round = 0; round < 3; ++round) r.refine();
    const LiveMemoryReport kept = r.memory();
    EXPECT_EQ(kept.links, 7u);
    EXPECT_EQ(registrar_->memory().links, 10u);  // Uncapped (the suite's registrar).
    for (std::size_t k = 0; k < scans_->size(); ++k) {
        const std::optional<PoseUpdate> pose = r.pose(static_cast<std::int64_t>(k + 1));
        ASSERT_TRUE(pose.has_value());
        const anascan::testing::PoseError e = anascan::testing::pose_error(
            pose->T_group_scan, scans_->front().T_true, (*scans_)[k].T_true,
            anascan::testing::centroid_of((*scans_)[k].cloud));
        EXPECT_LT(e.rotation_deg, 0.05) << "scan " << k + 1;
        EXPECT_LT(e.translation_m, 0.0002) << "scan " << k + 1;
    }
}

TEST_F(LiveRegistrationWalk, MemoryReportCountsTheReducedCopiesAndLinks) {
    const LiveMemoryReport m = registrar_->memory();
    EXPECT_EQ(m.scans, scans_->size());
    std::size_t points = 0;
    for (const LiveModelScan& s : registrar_->model()) points += s.cloud->size();
    // Positions and normals, 12 bytes each per point, at least.
    EXPECT_GE(m.cloud_bytes, points * 24);
    EXPECT_LT(m.cloud_bytes, points * 24 * 2);
    EXPECT_GT(m.tree_bytes, 0u);
    EXPECT_EQ(m.features_kept, 0u);  // The quick config computes none.
    EXPECT_GT(m.link_bytes, 0u);
    EXPECT_LE(m.link_bytes,
              m.links * quick_config().links.max_correspondences * sizeof(FineCorrespondence) * 2);
    EXPECT_EQ(m.total_bytes(),
              m.cloud_bytes + m.tree_bytes + m.feature_bytes + m.link_bytes + m.model_cache_bytes);
}

TEST_F(LiveRegistrationWalk, ARefineRoundStopsForANewScanAndGoesOnAfterIt) {
    const auto three_scans = [&] {
        auto r = std::make_unique<LiveRegistrar>(quick_config());
        for (std::int64_t seq = 1; seq <= 3; ++seq)
            EXPECT_TRUE(r->add({.seq = seq, .cloud = (*scans_)[seq - 1].cloud}).registered);
        return r;
    };
    const std::unique_ptr<LiveRegistrar> undisturbed = three_scans();
    undisturbed->refine();
    const std::size_t all_links = undisturbed->last_refine_report().new_links;
    ASSERT_GE(all_links, 2u);

    const std::unique_ptr<LiveRegistrar> r = three_scans();
    // A new scan waiting from the start: no link, no solve.
    EXPECT_TRUE(r->refine([] { return true; }).empty());
    EXPECT_TRUE(r->last_refine_report().interrupted);
    EXPECT_EQ(r->last_refine_report().new_links, 0u);
    // Rounds interrupted after ever more of their questions keep what they did; together
    // they make the links of one undisturbed round, and the first round left alone solves.
    std::size_t links = 0;
    bool partial = false;
    for (int n = 1; n < 50; ++n) {
        r->refine([n, asked = 0]() mutable { return ++asked > n; });
        const LiveRefineReport& report = r->last_refine_report();
        links += report.new_links;
        partial = partial || (report.interrupted && report.new_links > 0);
        if (!report.interrupted) {
            EXPECT_EQ(report.groups_refined, 1u);
            break;
        }
        EXPECT_EQ(report.groups_refined, 0u);
    }
    EXPECT_TRUE(partial);
    EXPECT_EQ(links, all_links);
}

TEST(LiveRegistration, UnusableScansAreReportedAndNotPlaced) {
    LiveRegistrar registrar;
    const LiveDecision empty = registrar.add({.seq = 1});
    EXPECT_FALSE(empty.registered);
    EXPECT_EQ(empty.method, LiveMethod::kUnusable);
    EXPECT_NE(empty.message.find("empty"), std::string::npos) << empty.message;

    PointCloud nan_cloud;
    const float nan = std::numeric_limits<float>::quiet_NaN();
    nan_cloud.positions.assign(100, Eigen::Vector3f(nan, 0.0f, 1.0f));
    const LiveDecision all_nan = registrar.add({.seq = 2, .cloud = nan_cloud});
    EXPECT_FALSE(all_nan.registered);
    EXPECT_NE(all_nan.message.find("non-finite"), std::string::npos) << all_nan.message;

    PointCloud few;
    for (int i = 0; i < 20; ++i) few.positions.emplace_back(0.01f * i, 0.0f, 1.0f);
    const LiveDecision tiny = registrar.add({.seq = 3, .cloud = few});
    EXPECT_FALSE(tiny.registered);
    EXPECT_NE(tiny.message.find("stone points"), std::string::npos) << tiny.message;
    EXPECT_EQ(registrar.group_count(), 0u);
    EXPECT_FALSE(registrar.pose(1).has_value());
}

/// A sphere of radius 0.15 m seen from 1 m (sensor frame): nothing like the block.
PointCloud sphere_scan() {
    PointCloud cloud;
    std::mt19937 rng(3);
    std::normal_distribution<float> g(0.0f, 1.0f);
    for (int i = 0; i < 20000; ++i) {
        Eigen::Vector3f d(g(rng), g(rng), g(rng));
        d.normalize();
        if (d.z() > 0.0f) d.z() = -d.z();  // The half facing the sensor.
        cloud.positions.push_back(Eigen::Vector3f(0, 0, 1.0f) + 0.15f * d);
    }
    return cloud;
}

TEST_F(LiveRegistrationWalk, AScanThatMatchesNothingOpensANewGroup) {
    LiveRegistrar registrar(quick_config());
    const LiveDecision first = registrar.add({.seq = 1, .cloud = (*scans_)[0].cloud});
    EXPECT_EQ(first.method, LiveMethod::kFirst);
    const LiveDecision other = registrar.add({.seq = 2, .cloud = sphere_scan()});
    EXPECT_TRUE(other.registered) << other.message;
    EXPECT_EQ(other.method, LiveMethod::kNewGroup) << other.message;
    EXPECT_EQ(other.group, 1);
    EXPECT_FALSE(other.attempts.empty());
    EXPECT_EQ(registrar.group_count(), 2u);
    EXPECT_TRUE(registrar.refine().empty());  // Nothing to merge: the sphere stays apart.
    EXPECT_EQ(registrar.group_count(), 2u);
}

}  // namespace
}  // namespace anascan::acquisition
