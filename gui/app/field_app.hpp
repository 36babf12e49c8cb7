#pragma once
/// \file
/// The field app: window, point view and panels until the window closes (interactive), or
/// until the headless driver has counted its frames (tests, measurements).

#include <cstddef>
#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include "anascan/gui/field_view_state.hpp"
#include "assembly_app.hpp"
#include "headless_driver.hpp"

namespace anascan::field {

/// The window and how the view draws.
struct ViewOptions {
    /// Window size, pixels; absent: the screen's.
    std::optional<int> width_px, height_px;
    float font_scale = 1.5f;
    bool high_contrast = false;
    gui::ColorMode color_mode = gui::ColorMode::kByScan;
    float point_size_px = 2.0f;     ///< Point size when every point is drawn.
    std::size_t point_budget = 0;   ///< LOD budget in points; 0: adapt to target_frame_ms.
    double target_frame_ms = 25.0;  ///< Frame time the adaptive LOD aims for.
};

/// Clouds shown without a session.
struct CloudInputs {
    std::vector<std::filesystem::path> clouds;  ///< PLY files, one scan each.
    std::size_t synthetic_points = 0;           ///< > 0: add a synthetic stone of this size.
    int synthetic_scans = 10;
};

/// The session and the scanner the capture action uses.
struct SessionOptions {
    std::optional<std::filesystem::path> dir;  ///< Session folder (opened or created).
    /// Active device at start; empty: the session's own (its newest scan's device), else
    /// the simulated small block.
    std::string device;
    int tour_views = 24;  ///< The simulated operator's tour around the block.
    int flip_after = -1;  ///< Turned over after this many views (-1: half the tour).
    std::optional<double> angular_step_deg;  ///< Terrestrial scanner setting, degrees.
    int sim_unplug_after = -1;               ///< Fault injection (simulated scanners).
    int worker_nice = 10;  ///< Capture/registration threads' nice value over the UI thread.
    /// A loaded scan goes to the GPU in steps of this many points a frame; 0: all in one
    /// frame, shuffled on the UI thread (as before the staged upload; for measuring).
    std::size_t upload_points_per_frame = 20'000;
    double mesh_resolution_mm = 1.0;  ///< Of the mesh the operator asks for (M).
    bool log_events = false;          ///< Session events on stdout, one line each.
};

struct FieldAppConfig {
    ViewOptions view;
    CloudInputs inputs;
    SessionOptions session;
    HeadlessConfig headless;   ///< Frames to draw, screenshot, the simulated operator.
    AssemblyOptions assembly;  ///< With a folder: the assembly view instead of the session.
    std::optional<std::filesystem::path> dump_state_json;  ///< The view state at the end.
};

/// Runs the app; returns the process exit code (errors are printed on stderr).
int run_field_app(const FieldAppConfig& config);

}  // namespace anascan::field
