#include "anascan/sim/sim_structured_light_scanner.hpp"

#include <cstdio>

#include "anascan/drivers/structured_light/stereo_decoder.hpp"
#include "sim_capture_run.hpp"
#include "sim_scanner_parts.hpp"

namespace anascan::sim {
namespace {

using drivers::DeviceSettings;

constexpr double kReferenceExposureUs = 10000.0;  ///< Renders with config.render.exposure_dn.

drivers::Capabilities sl_capabilities() {
    drivers::Capabilities caps;
    caps.can_capture_scan = true;
    caps.exposure_us = drivers::NumericRange{1000.0, 40000.0};
    caps.range_m = drivers::NumericRange{0.5, 3.0};  // the PT-M 1024's working range
    return caps;
}

drivers::sl::CameraIntrinsics intrinsics(const PinholeModel& camera) {
    drivers::sl::CameraIntrinsics c;
    c.K << camera.fx_px, 0.0, camera.cx_px, 0.0, camera.fy_px, camera.cy_px, 0.0, 0.0, 1.0;
    c.width_px = camera.width_px;
    c.height_px = camera.height_px;
    return c;
}

/// The calibration a perfect calibration of the rig gives (no distortion).
drivers::sl::StereoCalibration rig_calibration(const StructuredLightRig& rig) {
    return {.cam1 = intrinsics(rig.cam1),
            .cam2 = intrinsics(rig.cam2),
            .T_cam1_cam2 = rig.cam1.T_world_device.inverse() * rig.cam2.T_world_device};
}

drivers::sl::StereoDecodeConfig decode_config(const StructuredLightRenderConfig& render,
                                              const DeviceSettings& settings) {
    drivers::sl::StereoDecodeConfig c;
    c.sequence.gray = {.projector_width_px = render.patterns.width_px,
                       .projector_height_px = render.patterns.height_px};
    if (render.patterns.phase_steps > 0)
        c.sequence.phase = drivers::sl::PhaseShiftLayout{
            .period_px = static_cast<int>(render.patterns.phase_period_px),
            .steps = render.patterns.phase_steps};
    c.triangulation.min_depth_m = *settings.min_range_m;
    c.triangulation.max_depth_m = *settings.max_range_m;
    return c;
}

}  // namespace

std::unique_ptr<SimStructuredLightScanner> SimStructuredLightScanner::open(
    SimStructuredLightConfig config) {
    config.render.patterns.width_px = config.rig.projector_width_px;
    config.render.patterns.height_px = config.rig.projector_height_px;
    return std::unique_ptr<SimStructuredLightScanner>(
        new SimStructuredLightScanner(std::move(config)));
}

SimStructuredLightScanner::SimStructuredLightScanner(SimStructuredLightConfig config)
    : SimScanner(detail::scanner_parts(
          config, "simulated PT-M 1024 structured light", DeviceKind::kStructuredLight,
          sl_capabilities(),
          {.exposure_us = kReferenceExposureUs, .min_range_m = 0.5, .max_range_m = 3.0})),
      config_(std::move(config)),
      station_(config_.station) {}

std::string SimStructuredLightScanner::calibration_json() const {
    const StructuredLightRig r = rig();
    char json[256];
    std::snprintf(json, sizeof(json),
                  "{\"scene\": \"%s\", \"camera_size_px\": [%d, %d], \"camera_focal_px\": %g, "
                  "\"baseline_m\": %g, \"projector_size_px\": [%d, %d]}",
                  scene().name.c_str(), r.cam1.width_px, r.cam1.height_px, r.cam1.fx_px,
                  config_.rig.baseline_m, r.projector.width_px, r.projector.height_px);
    return json;
}

StructuredLightRig SimStructuredLightScanner::rig() const {
    // Aim at the middle of the block's upper half (as `anascan sim sl-capture`).
    const Eigen::Vector3d size = scene().block.size_m;
    const Eigen::Vector3d target =
        block_pose(scene().placement, size).translation() + Eigen::Vector3d(0, 0, 0.25 * size.z());
    return make_structured_light_rig(config_.rig, sensor_looking_at(target, station_));
}

Expected<Scan> SimStructuredLightScanner::capture_scan(const drivers::CaptureControl& control) {
    auto world = begin_capture();
    if (!world) return fail(world.error());
    detail::SimCaptureRun run(control, info().uri, faults());
    const auto stopped = [&] {
        if (run.unplugged()) set_unplugged();
        return fail(run.stop_reason());
    };
    const drivers::DeviceSettings now = settings();
    const StructuredLightRig head = rig();
    StructuredLightRenderConfig render = config_.render;
    render.exposure_dn *= *now.exposure_us / kReferenceExposureUs;
    render.seed += static_cast<std::uint64_t>(sequence());  // new noise each capture
    if (!run.keep_going(0.0, "projecting the patterns")) return stopped();
    auto images = render_structured_light((*world)->caster, (*world)->albedos, head, render);
    if (!images) return fail(images.error().code, info().uri + ": " + images.error().message);
    if (!run.keep_going(0.6, "decoding")) return stopped();
    auto decoded = drivers::sl::decode_stereo(images->cam1, images->cam2, rig_calibration(head),
                                              decode_config(render, now));
    if (!decoded) return fail(decoded.error().code, info().uri + ": " + decoded.error().message);
    if (!run.keep_going(1.0, "scan complete")) return stopped();
    Scan scan;
    scan.cloud = std::move(decoded->cloud);
    stamp(scan, head.cam1.T_world_device);
    station_.azimuth_deg += config_.advance_deg;
    return scan;
}

}  // namespace anascan::sim
