#include "anascan/sim/sim_structured_light_scanner.hpp"

#include <cstdio>

#include "anascan/drivers/structured_light/stereo_decoder.hpp"
#include "anascan/sim/sim_projector.hpp"
#include "sim_capture_run.hpp"
#include "sim_scanner_parts.hpp"

namespace anascan::sim {
namespace {

using drivers::DeviceSettings;

constexpr double kReferenceExposureUs = 10000.0;  ///< Renders with config.render.exposure_dn.
constexpr drivers::NumericRange kWorkingRangeM{0.5, 3.0};  // the PT-M 1024's

drivers::Capabilities sl_capabilities() {
    drivers::Capabilities caps;
    caps.can_capture_scan = true;
    caps.exposure_us = drivers::NumericRange{1000.0, 40000.0};
    caps.range_m = kWorkingRangeM;
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

drivers::sl::StereoDecodeConfig decode_config(const StructuredLightRenderConfig& render) {
    drivers::sl::StereoDecodeConfig c;
    c.sequence.gray = {.projector_width_px = render.patterns.width_px,
                       .projector_height_px = render.patterns.height_px};
    if (render.patterns.phase_steps > 0)
        c.sequence.phase = drivers::sl::PhaseShiftLayout{
            .period_px = static_cast<int>(render.patterns.phase_period_px),
            .steps = render.patterns.phase_steps};
    return c;
}

/// The head as drivers::StructuredLightScanner composes it, from simulated parts.
struct SimHead {
    drivers::StructuredLightParts parts;
    SimCamera* cam1 = nullptr;
    SimCamera* cam2 = nullptr;
};

SimHead sim_head(const SimStructuredLightConfig& c,
                 const std::shared_ptr<SimDeviceFaults> (&faults)[3]) {
    auto screen = std::make_shared<SimProjectorScreen>();
    SimHead head;
    auto camera = [&](int index) {
        auto cam = std::make_unique<SimCamera>(
            SimCameraConfig{.uri = c.uri + "#cam" + std::to_string(index),
                            .width_px = c.rig.camera_width_px,
                            .height_px = c.rig.camera_height_px,
                            .camera_index = index,
                            .screen = screen,
                            .faults = faults[index - 1],
                            .stale_frame_after_switch = c.stale_frame_after_switch});
        (index == 1 ? head.cam1 : head.cam2) = cam.get();
        return cam;
    };
    head.parts.info = {.uri = c.uri, .model = "simulated PT-M 1024 structured light"};
    head.parts.cam1 = camera(1);
    head.parts.cam2 = camera(2);
    head.parts.projector =
        std::make_unique<SimProjector>(c.uri + "#projector", c.rig.projector_width_px,
                                       c.rig.projector_height_px, screen, faults[2]);
    head.parts.calibration = rig_calibration(make_structured_light_rig(c.rig, Pose::Identity()));
    head.parts.decode = decode_config(c.render);
    head.parts.range_m = kWorkingRangeM;
    return head;
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
      station_(config_.station) {
    for (auto& f : part_faults_) f = std::make_shared<SimDeviceFaults>();
    SimHead head = sim_head(config_, part_faults_);
    cam1_ = head.cam1;
    cam2_ = head.cam2;
    // The parts are made for each other: creation cannot fail.
    head_ = std::move(*drivers::StructuredLightScanner::create(std::move(head.parts)));
}

const std::shared_ptr<SimDeviceFaults>& SimStructuredLightScanner::part_faults(SlPart part) const {
    return part_faults_[static_cast<int>(part)];
}

void SimStructuredLightScanner::close() {
    SimScanner::close();
    head_->close();
}

void SimStructuredLightScanner::set_camera_views(const StructuredLightRig& head,
                                                 const std::shared_ptr<const SimWorld>& world) {
    StructuredLightRenderConfig render = config_.render;
    render.seed += static_cast<std::uint64_t>(sequence());  // new noise each capture
    cam1_->set_view({world, head.cam1, head.projector, render});
    cam2_->set_view({world, head.cam2, head.projector, render});
    parts_placed_ = true;
}

void SimStructuredLightScanner::place_parts(const StructuredLightRig& head,
                                            const std::shared_ptr<const SimWorld>& world) {
    set_camera_views(head, world);
    cam1_->set_device_faults(faults());
    // The whole device going away: the projector leaves half-way through the patterns.
    if (detail::take_from_budget(faults().get()))
        part_faults(SlPart::kProjector)->unplug_after_captures =
            static_cast<int>(decode_config(config_.render).sequence.image_count() / 2);
}

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
    const Eigen::Vector3d target = aim_ ? *aim_
                                        : block_pose(scene().placement, size).translation() +
                                              Eigen::Vector3d(0, 0, 0.25 * size.z());
    return make_structured_light_rig(config_.rig, sensor_looking_at(target, station_));
}

Expected<Scan> SimStructuredLightScanner::capture_scan(const drivers::CaptureControl& control) {
    auto world = begin_capture();
    if (!world) return fail(world.error());
    const StructuredLightRig head = rig();
    place_parts(head, *world);
    if (auto ok = head_->configure(settings()); !ok) return fail(ok.error());
    head_settings_ = settings();
    auto scan = head_->capture_scan(control);
    if (!scan) {
        if (scan.error().code == ErrorCode::kDisconnected) set_unplugged();
        return fail(scan.error());
    }
    stamp(*scan, head.cam1.T_world_device);
    station_.azimuth_deg += config_.advance_deg;
    return with_output_faults(std::move(*scan));
}

Expected<std::vector<drivers::Frame>> SimStructuredLightScanner::preview_frames(
    std::chrono::milliseconds timeout) {
    auto world = begin_capture();
    if (!world) return fail(world.error());
    if (!parts_placed_) set_camera_views(rig(), *world);  // no fault budget: not a capture
    // Configuring the cameras drops their rendered images: only when the settings changed.
    if (head_settings_ != settings()) {
        if (auto ok = head_->configure(settings()); !ok) return fail(ok.error());
        head_settings_ = settings();
    }
    auto frames = head_->preview_frames(timeout);
    if (!frames && frames.error().code == ErrorCode::kDisconnected) set_unplugged();
    return frames;
}

}  // namespace anascan::sim
