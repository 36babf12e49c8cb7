#pragma once
// A simulated scanning session for coverage (shared by the test and the measuring tool):
// structured-light views around the small block, the block turned over after
// `flip_after` views; every scan's true pose expressed in the frame of the first
// placement's world (T_world0_scan = T_world0_block0 * T_world_block_now^-1 *
// T_world_scan), the ground-truth stone mesh in that frame.

#include <cstdio>
#include <vector>

#include "anascan/processing/coverage/coverage.hpp"
#include "anascan/sim/sim_structured_light_scanner.hpp"

namespace anascan::sim::test {

struct CoverageSessionConfig {
    int views = 24;
    int flip_after = 12;
    SceneConfig scene = *named_scene("small-block");
    StructuredLightRigConfig rig = SimStructuredLightConfig{}.rig;
    bool progress = false;  ///< One line per capture on stderr.
};

struct CoverageSession {
    std::vector<Scan> scans;  ///< T_world_scan in the first placement's world.
    Mesh stone_world0;        ///< Ground-truth stone surface, same frame.
};

/// Where view i of a placement stands: around the block, low (the lower sides and the
/// ground; the rig aims at the block's upper half) and high in turn.
inline Viewpoint coverage_viewpoint(int i, int count) {
    const bool low = i % 2 == 0;
    return Viewpoint{.azimuth_deg = 15.0 + 360.0 * i / count,
                     .elevation_deg = low ? 15.0 : 45.0,
                     .distance_m = low ? 1.6 : 1.2};
}

inline Expected<CoverageSession> simulate_coverage_session(const CoverageSessionConfig& config) {
    auto device = SimStructuredLightScanner::open(
        {.scene = config.scene, .rig = config.rig, .advance_deg = 0.0});
    CoverageSession session;
    Pose T_world0_block0 = Pose::Identity();
    for (int i = 0; i < config.views; ++i) {
        const bool turned = i >= config.flip_after;
        if (i == config.flip_after)
            device->place_block({.resting_face = BlockFace::kPosZ, .yaw_deg = -30.0});
        const int first = turned ? config.flip_after : 0;
        const int count = turned ? config.views - config.flip_after : config.flip_after;
        device->move_to(coverage_viewpoint(i - first, count));
        auto scan = device->capture_scan({});
        if (!scan) return fail(scan.error());
        auto world = device->world();
        if (!world) return fail(world.error());
        if (i == 0) {
            T_world0_block0 = (*world)->scene.T_world_block;
            session.stone_world0 = surface_mesh((*world)->scene, SurfaceKind::kStone);
        }
        scan->meta.T_world_scan =
            T_world0_block0 * (*world)->scene.T_world_block.inverse() * *scan->meta.T_world_scan;
        if (config.progress)
            std::fprintf(stderr, "view %d/%d: %zu points%s\n", i + 1, config.views,
                         scan->cloud.size(), turned ? " (turned over)" : "");
        session.scans.push_back(std::move(*scan));
    }
    return session;
}

/// Coverage views of the first `count` scans.
inline std::vector<CoverageScanView> coverage_views(const CoverageSession& session,
                                                    std::size_t count) {
    std::vector<CoverageScanView> views;
    for (std::size_t i = 0; i < count && i < session.scans.size(); ++i) {
        const Scan& scan = session.scans[i];
        views.push_back({.cloud = &scan.cloud,
                         .T_world_scan = *scan.meta.T_world_scan,
                         .sensor_origin_scan_m = scan.meta.sensor_origin_scan_m});
    }
    return views;
}

}  // namespace anascan::sim::test
