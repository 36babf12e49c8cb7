#pragma once
/// \file
/// The field app's main loop: window, point view and panels, until the window closes or
/// `frames` frames are drawn; then the screenshot and the frame-time report.

#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include "anascan/gui/field_view_state.hpp"

namespace anascan::field {

struct FieldAppConfig {
    std::vector<std::filesystem::path> clouds;  ///< PLY files, one scan each.
    std::size_t synthetic_points = 0;           ///< > 0: add a synthetic stone of this size.
    int synthetic_scans = 10;
    std::optional<std::filesystem::path> screenshot_png;
    int frames = 0;                   ///< 0: run until the window is closed.
    std::size_t point_budget = 0;     ///< LOD budget in points; 0: adapt to target_frame_ms.
    double target_frame_ms = 25.0;    ///< Frame time the adaptive LOD aims for.
    float point_size_px = 2.0f;       ///< Point size when every point is drawn.
    double orbit_px_per_frame = 0.0;  ///< Turn the camera every frame (measuring interaction).
    int width_px = 1280, height_px = 800;
    float font_scale = 1.5f;
    bool high_contrast = false;
    gui::ColorMode color_mode = gui::ColorMode::kByScan;
    std::optional<std::filesystem::path> session;  ///< Session folder (opened or created).
    std::string device = "sim:structured-light/small-block";  ///< Active device at start.
    int capture_views = 0;            ///< Headless: this many captures through the capture action.
    std::int64_t reregister_seq = 0;  ///< Headless: re-register this scan once settled (0: none).
    bool connect_device = false;      ///< Headless: the device panel's "Connect" at start.
    std::vector<std::string>
        apply_settings;   ///< Headless: KEY=VALUE typed and applied once settled.
    int tour_views = 24;  ///< The simulated operator's tour around the block.
    int flip_after = -1;  ///< Turned over after this many views (-1: half the tour).
    std::optional<double> angular_step_deg;  ///< Terrestrial scanner setting, degrees.
    int sim_unplug_after = -1;               ///< Fault injection (simulated scanners).
    int worker_nice = 10;  ///< Capture/registration threads' nice value over the UI thread.
    /// A loaded scan goes to the GPU in steps of this many points a frame; 0: all in one
    /// frame, shuffled on the UI thread (as before the staged upload; for measuring).
    std::size_t upload_points_per_frame = 20'000;
    std::optional<std::filesystem::path> dump_state_json;  ///< The view state at the end.
    double session_timeout_s = 600.0;  ///< Headless: give up waiting for the session.
};

/// Runs the app; returns the process exit code (errors are printed on stderr).
int run_field_app(const FieldAppConfig& config);

}  // namespace anascan::field
