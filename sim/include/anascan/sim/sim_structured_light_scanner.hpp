#pragma once
/// \file
/// The simulated structured-light scanner as a device (`sim:structured-light[/SCENE]`): a
/// drivers::Scanner whose capture_scan renders the pattern sequence onto the scene as both
/// cameras see it (structured_light_renderer.hpp) and decodes it with the real pipeline
/// (drivers' decode_stereo), returning the cloud in cam1's frame with its true pose.

#include <memory>
#include <string>

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
};

/// The device. Settings: exposure_us (scales the rendered brightness; 10000 us = the
/// renderer's exposure_dn) and min/max_range_m (depths kept, along cam1's axis). Not
/// thread-safe (see drivers::Scanner).
class SimStructuredLightScanner final : public SimScanner {
public:
    /// Opens at once; the scene is built at the first capture.
    static std::unique_ptr<SimStructuredLightScanner> open(SimStructuredLightConfig config);

    std::string calibration_json() const override;
    /// Renders, then decodes: a stop or the timeout is seen between the two stages.
    Expected<Scan> capture_scan(const drivers::CaptureControl& control) override;

    /// Sim-only: the viewpoint of the next capture.
    void move_to(const Viewpoint& station) { station_ = station; }
    /// The rig of the next capture, with its true poses.
    StructuredLightRig rig() const;

private:
    explicit SimStructuredLightScanner(SimStructuredLightConfig config);

    SimStructuredLightConfig config_;
    Viewpoint station_;
};

}  // namespace anascan::sim
