// CaptureSession with a simulated scanner and a real session store: captures are
// acknowledged in order, decided by the registration worker, device errors become events
// and the session goes on when the device is back.
#include <gtest/gtest.h>
#include <unistd.h>

#include <algorithm>
#include <filesystem>
#include <mutex>

#include "anascan/acquisition/capture/capture_session.hpp"
#include "anascan/sim/scanning_tour.hpp"
#include "capture_session_fixture.hpp"
#include "live_session_sim.hpp"
#include "sim_devices_fixture.hpp"

namespace anascan::acquisition {
namespace {

TEST_F(CaptureSessionTest, ScansAreAcknowledgedInOrderAndEachIsDecided) {
    int opened = 0;
    auto session = start({.coverage_live = false});
    ASSERT_TRUE(session->attach_scanner("sim:tof/small-block", tof_opener(nullptr, &opened)));
    std::vector<std::int64_t> seqs;
    for (int i = 0; i < 3; ++i) {
        auto ack = session->capture({}).get();
        ASSERT_TRUE(ack) << ack.error().message;
        seqs.push_back(*ack);
    }
    EXPECT_EQ(seqs, (std::vector<std::int64_t>{1, 2, 3}));
    session->wait_until_idle();
    auto scans = session->store().scans();
    ASSERT_TRUE(scans);
    ASSERT_EQ(scans->size(), 3u);
    for (const ScanRecord& s : *scans) {
        EXPECT_NE(s.state, ScanState::kQueued) << "scan " << s.seq << " never decided";
        EXPECT_TRUE(fs::exists(dir_ / s.file)) << s.file;
    }
    EXPECT_EQ(count(SessionEventKind::kSaved), 3u);
    EXPECT_EQ(count(SessionEventKind::kRegistered) + count(SessionEventKind::kRegistrationFailed),
              3u);
    EXPECT_EQ(opened, 1);
}

TEST_F(CaptureSessionTest, AReopenedSessionRefinesBetweenItsScansAsTheCaptureDid) {
    {
        // Three ray-cast views 12° apart, saved as a capture would have saved them.
        sim::SceneConfig config = sim::named_scene("small-block").value();
        config.block.grid_step_m = 0.003;
        config.with_tent = false;
        const sim::Scene scene = sim::make_scene(config);
        const sim::RayCaster caster = sim::RayCaster::create(scene.mesh).value();
        auto store = SessionStore::open(dir_, SessionOpenMode::kCreateOrOpen);
        ASSERT_TRUE(store) << store.error().message;
        for (int k = 0; k < 3; ++k) {
            Scan scan;
            scan.meta.device_id = "sim:test#0";
            scan.meta.device_kind = DeviceKind::kStructuredLight;
            scan.meta.sensor_origin_scan_m = Eigen::Vector3d::Zero();
            scan.meta.time = std::chrono::system_clock::now();
            const sim::Viewpoint view{
                .azimuth_deg = 30.0 + 12.0 * k, .elevation_deg = 35.0, .distance_m = 1.1};
            scan.cloud = anascan::testing::pinhole_scan(
                caster, sim::sensor_looking_at(anascan::testing::aim_point(scene), view),
                {.width_px = 300, .height_px = 225, .focal_px = 510.0},
                static_cast<std::uint32_t>(k + 1));
            ASSERT_TRUE((*store)->save_scan(scan, std::nullopt));
        }
    }
    // Reopened, the three scans are registered again from the store, all queued at once. The
    // background work runs after each of them, as it did between live captures: the links
    // (and the session's RMS gate) exist before the next scan is decided.
    auto session = start({.coverage_live = false});
    session->wait_until_idle();
    std::lock_guard lock(mutex_);
    std::vector<SessionEventKind> kinds;
    for (const SessionEvent& e : events_)
        if (e.kind == SessionEventKind::kRegistered || e.kind == SessionEventKind::kPosesRefined)
            kinds.push_back(e.kind);
    ASSERT_EQ(std::count(kinds.begin(), kinds.end(), SessionEventKind::kRegistered), 3);
    const auto last_registered =
        std::find(kinds.rbegin(), kinds.rend(), SessionEventKind::kRegistered);
    EXPECT_NE(std::find(last_registered, kinds.rend(), SessionEventKind::kPosesRefined),
              kinds.rend())
        << "no refinement before the last scan was registered";
}

TEST_F(CaptureSessionTest, AScanCanBeRegisteredAgainButNotAnUnknownOrExcludedOne) {
    int opened = 0;
    auto session = start({.coverage_live = false});
    ASSERT_TRUE(session->attach_scanner("sim:tof/small-block", tof_opener(nullptr, &opened)));
    for (int i = 0; i < 3; ++i) ASSERT_TRUE(session->capture({}).get());
    session->wait_until_idle();
    const std::size_t decided =
        count(SessionEventKind::kRegistered) + count(SessionEventKind::kRegistrationFailed);

    ASSERT_TRUE(session->reregister(2));
    session->wait_until_idle();
    EXPECT_EQ(count(SessionEventKind::kRegistered) + count(SessionEventKind::kRegistrationFailed),
              decided + 1);
    auto scan = session->store().scan(2);
    ASSERT_TRUE(scan);
    EXPECT_NE(scan->state, ScanState::kQueued);
    auto events = session->store().events();
    ASSERT_TRUE(events);
    EXPECT_TRUE(std::any_of(events->begin(), events->end(),
                            [](const EventRecord& e) { return e.kind == "reregister"; }));

    auto unknown = session->reregister(99);
    ASSERT_FALSE(unknown);
    EXPECT_NE(unknown.error().message.find("99"), std::string::npos) << unknown.error().message;
    ASSERT_TRUE(session->exclude(3, true));
    auto excluded = session->reregister(3);
    ASSERT_FALSE(excluded);
    EXPECT_NE(excluded.error().message.find("excluded"), std::string::npos)
        << excluded.error().message;
}

TEST_F(CaptureSessionTest, UnpluggedMidScanIsAnEventAndTheSessionGoesOnWhenItIsBack) {
    auto faults = std::make_shared<sim::SimDeviceFaults>();
    faults->unplug_after_captures = 1;
    int opened = 0;
    auto session = start({.register_live = false});
    ASSERT_TRUE(session->attach_scanner("sim:tof/small-block", tof_opener(faults, &opened)));
    ASSERT_TRUE(session->capture({}).get());
    auto lost = session->capture({}).get();
    ASSERT_FALSE(lost);
    EXPECT_EQ(lost.error().code, ErrorCode::kDisconnected);
    EXPECT_NE(lost.error().message.find("sim:tof/small-block"), std::string::npos)
        << lost.error().message;
    auto back = session->capture({}).get();
    ASSERT_TRUE(back) << back.error().message;
    EXPECT_EQ(*back, 2);  // the failed capture used no sequence number
    session->wait_until_idle();
    EXPECT_EQ(count(SessionEventKind::kDeviceError), 1u);
    EXPECT_EQ(count(SessionEventKind::kDeviceBack), 1u);
    EXPECT_EQ(opened, 2);
    auto scans = session->store().scans();
    ASSERT_TRUE(scans);
    EXPECT_EQ(scans->size(), 2u);
}

TEST_F(CaptureSessionTest, TrueTransformMakesTheDevicePoseTruthNotAPrior) {
    int opened = 0;
    auto session = start({.register_live = false});
    ASSERT_TRUE(session->attach_scanner("sim:tof/small-block", tof_opener(nullptr, &opened)));
    const Pose shift(Eigen::Translation3d(0.1, 0.2, 0.3));
    auto ack =
        session->capture({.before = [&](drivers::Scanner&) { return std::optional<Pose>(shift); }})
            .get();
    ASSERT_TRUE(ack) << ack.error().message;
    session->wait_until_idle();
    auto scans = session->store().scans();
    ASSERT_TRUE(scans);
    ASSERT_EQ(scans->size(), 1u);
    ASSERT_TRUE((*scans)[0].true_pose);
    EXPECT_FALSE((*scans)[0].pose_prior);
    auto scan = session->store().load_scan(1);
    ASSERT_TRUE(scan) << scan.error().message;
    EXPECT_FALSE(scan->meta.T_world_scan) << "the truth must not reach registration";
}

}  // namespace
}  // namespace anascan::acquisition
