#pragma once
/// \file
/// The simulated structured-light scanner as a device (`sim:structured-light[/SCENE]`): the
/// same drivers::StructuredLightScanner as real hardware, composed of a simulated projector
/// (sim_projector.hpp) and two simulated cameras (sim_camera.hpp) that render the scene
/// lit by the pattern on show; the real pipeline decodes. The cloud is in cam1's frame
/// with its true pose.

#include <memory>
#include <optional>
#include <string>

#include "anascan/drivers/structured_light_scanner.hpp"
#include "anascan/sim/sim_camera.hpp"
#include "anascan/sim/sim_scanner.hpp"
#include "anascan/sim/structured_light_renderer.hpp"
#include "anascan/sim/structured_light_rig.hpp"
#include "anascan/sim/viewpoints.hpp"

namespace anascan::sim {

struct SimStructuredLightConfig {
    std::string uri = "sim:structured-light";  ///< Names the device in info() and errors.
    SceneConfig scene;                         ///< What it looks at.
    /// The PT-M 1024-like rig scaled by 0.4 (cameras 640 x 480, f 1080 px: 0.93 mm per
    /// pixel at 1 m; projector 512 x 320, f 680 px), so a capture takes seconds. The
    /// projector scales with the cameras: a camera pixel must stay smaller than a projector
    /// pixel for the finest Gray-code bits to be resolved.
    StructuredLightRigConfig rig{.camera_width_px = 640,
                                 .camera_height_px = 480,
                                 .camera_focal_px = 1080.0,
                                 .projector_width_px = 512,
                                 .projector_height_px = 320,
                                 .projector_focal_px = 680.0};
    StructuredLightRenderConfig render;  ///< Photometry and noise (exposure is a setting).
    /// Where the head stands around the upper half of the block, for the first capture.
    Viewpoint station{.azimuth_deg = 30.0, .elevation_deg = 35.0, .distance_m = 1.0};
    double advance_deg = 60.0;              ///< Moves around the block after each capture; 0 stays.
    std::shared_ptr<SimWorldCache> worlds;  ///< Shared scenes; empty: a private cache.
    std::shared_ptr<SimDeviceFaults> faults;  ///< Injected unplug/stall; may be empty.
    /// Each camera delivers one stale frame after every pattern switch (the scanner must
    /// drop it); tests of the synchronisation.
    bool stale_frame_after_switch = false;
};

/// The parts of the head, each with its own injected faults (SimStructuredLightScanner::
/// part_faults): a camera counts frames, the projector patterns.
enum class SlPart { kCam1, kCam2, kProjector };

/// The device. Settings: exposure_us (the cameras'; 10000 us = the renderer's exposure_dn)
/// and min/max_range_m (depths kept, along cam1's axis). The whole device's faults
/// (set_faults): an unplug takes the projector away half-way through the patterns, a stall
/// silences cam1. Not thread-safe (see drivers::Scanner).
class SimStructuredLightScanner final : public SimScanner {
public:
    /// Opens at once; the scene is built at the first capture.
    static std::unique_ptr<SimStructuredLightScanner> open(SimStructuredLightConfig config);

    std::string calibration_json() const override;
    /// Closes the cameras too.
    void close() override;
    /// Places the cameras, then drivers::StructuredLightScanner::capture_scan: show each
    /// pattern, take each camera's frame of it, decode.
    Expected<Scan> capture_scan(const drivers::CaptureControl& control) override;
    /// The cameras' view under the projector's white: where the last capture left them
    /// (their images are rendered already), or at the next station before the first.
    Expected<std::vector<drivers::Frame>> preview_frames(
        std::chrono::milliseconds timeout) override;

    /// Sim-only: the viewpoint of the next capture.
    void move_to(const Viewpoint& station) { station_ = station; }
    /// Sim-only: the point the station's viewpoint is around, world frame; absent (the
    /// default): the middle of the block's upper half.
    void aim_at(std::optional<Eigen::Vector3d> target_world_m) { aim_ = target_world_m; }
    /// The rig of the next capture, with its true poses.
    StructuredLightRig rig() const;
    /// Sim-only: the faults of one part (unplug or silence one camera or the projector).
    const std::shared_ptr<SimDeviceFaults>& part_faults(SlPart part) const;
    /// What the last capture saw (stale frames dropped, ...).
    const drivers::StructuredLightCaptureStats& last_capture() const {
        return head_->last_capture();
    }

private:
    explicit SimStructuredLightScanner(SimStructuredLightConfig config);
    void place_parts(const StructuredLightRig& head, const std::shared_ptr<const SimWorld>& world);
    void set_camera_views(const StructuredLightRig& head,
                          const std::shared_ptr<const SimWorld>& world);

    SimStructuredLightConfig config_;
    Viewpoint station_;
    std::optional<Eigen::Vector3d> aim_;
    std::shared_ptr<SimDeviceFaults> part_faults_[3];
    SimCamera* cam1_ = nullptr;  ///< Owned by head_.
    SimCamera* cam2_ = nullptr;
    std::unique_ptr<drivers::StructuredLightScanner> head_;
    bool parts_placed_ = false;  ///< The cameras have a view (a capture or preview placed them).
    std::optional<drivers::DeviceSettings> head_settings_;  ///< Last given to head_.
};

}  // namespace anascan::sim
