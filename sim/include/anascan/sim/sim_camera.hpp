#pragma once
/// \file
/// A simulated camera of sim:structured-light: a drivers::Camera whose frames are the
/// scene as its pinhole sees it, lit by what the simulated projector shows at that moment
/// (SimProjectorScreen) and the ambient light, rendered by structured_light_renderer.hpp
/// (projector and camera blur, shadows, occlusion, sensor noise).

#include <memory>
#include <optional>
#include <string>

#include "anascan/drivers/camera.hpp"
#include "anascan/sim/sim_device_faults.hpp"
#include "anascan/sim/sim_projector.hpp"
#include "anascan/sim/sim_world.hpp"
#include "anascan/sim/structured_light_renderer.hpp"

namespace anascan::sim {

struct SimCameraConfig {
    std::string uri;  ///< Names it: "sim:structured-light/small-block#cam1".
    int width_px = 640;
    int height_px = 480;
    int camera_index = 1;  ///< Draws its own noise (1 or 2).
    std::shared_ptr<SimProjectorScreen> screen;
    /// unplug_after_captures counts frames; stalled: no frame (kTimeout). May be empty.
    std::shared_ptr<SimDeviceFaults> faults;
    /// Models a frame queued in the driver: after the projector changes, the first frame
    /// delivered is the previous one again, with its old time stamp (a stale frame).
    bool stale_frame_after_switch = false;
};

/// Where the camera is and what it looks at (set between captures).
struct SimCameraView {
    std::shared_ptr<const SimWorld> world;
    PinholeModel camera;     ///< With its true pose.
    PinholeModel projector;  ///< The projector lighting the scene, with its pose.
    /// Photometry and noise seed; exposure_dn is for exposure_us = 10000 and scales with it.
    StructuredLightRenderConfig render;
};

/// Not thread-safe (see drivers::Camera). Settings: exposure_us in [1000, 40000], one
/// grey8 stream of the configured size. Renders ahead: at the first frame of a view it
/// renders the projector's whole loaded sequence at once (TBB over the patterns, as a
/// batch renderer would), then each frame is the image of the pattern on show; the noise of
/// pattern i is drawn from its index, so the images are those of rendering on demand.
class SimCamera final : public drivers::Camera {
public:
    explicit SimCamera(SimCameraConfig config);

    const drivers::DeviceInfo& info() const override { return info_; }
    const drivers::Capabilities& capabilities() const override { return caps_; }
    drivers::DeviceSettings settings() const override { return settings_; }
    Expected<void> configure(const drivers::DeviceSettings& requested) override;
    void close() override;
    Expected<void> start_stream() override;
    Expected<drivers::Frame> next_frame(std::chrono::milliseconds timeout) override;
    void stop_stream() override { streaming_ = false; }

    /// Sim-only: the pose and scene of the next frames (traced at the next frame).
    void set_view(SimCameraView view);
    /// Sim-only: a second source of stalls (the whole device's injected faults).
    void set_device_faults(std::shared_ptr<SimDeviceFaults> faults) {
        device_faults_ = std::move(faults);
    }

private:
    Expected<void> check_usable();
    bool stalled() const;
    drivers::Frame render(std::chrono::nanoseconds start, const SimProjectorScreen::Showing& s);
    cv::Mat image_of(const SimProjectorScreen::Showing& showing,
                     const StructuredLightRenderConfig& render);

    SimCameraConfig config_;
    drivers::DeviceInfo info_;
    drivers::Capabilities caps_;
    drivers::DeviceSettings settings_;
    std::shared_ptr<SimDeviceFaults> device_faults_;
    std::optional<SimCameraView> view_;
    std::optional<CameraSurface> surface_;  ///< Of view_, traced on first use.
    std::shared_ptr<const SimProjectorScreen::Images> ahead_of_;  ///< What ahead_ renders.
    std::vector<cv::Mat> ahead_;  ///< The loaded sequence as this camera sees it.
    std::optional<drivers::Frame> last_;
    std::uint64_t last_serial_ = 0;  ///< Projector serial of last_.
    std::uint64_t sequence_ = 0;
    std::size_t rendered_ = 0;  ///< Frames rendered in this stream (noise index).
    bool streaming_ = false;
    bool closed_ = false;
    bool gone_ = false;
};

}  // namespace anascan::sim
