#pragma once
/// \file
/// Headless runs (tests, measurements) drive the app as an operator would: the capture
/// button until `capture_views` captures have finished, then wait until the session has
/// settled (registration done, points loaded), press the device panel's buttons, re-register
/// a scan, make the mesh and settle again; then `frames` frames are counted and the last is the
/// screenshot. An interactive run (frames == 0) has nothing to drive.

#include <cstdint>
#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include "anascan/gui/ui_action.hpp"
#include "anascan/processing/core/expected.hpp"
#include "anascan/processing/core/stopwatch.hpp"

namespace anascan::field {

struct AppState;
class FieldWindow;

struct HeadlessConfig {
    int frames = 0;  ///< 0: interactive (run until the window is closed).
    std::optional<std::filesystem::path> screenshot_png;  ///< The last counted frame.
    int capture_views = 0;                    ///< This many captures through the capture action.
    std::int64_t reregister_seq = 0;          ///< Re-register this scan once settled (0: none).
    bool connect_device = false;              ///< The device panel's "Connect" at start.
    std::vector<std::string> apply_settings;  ///< KEY=VALUE typed and applied once settled.
    bool make_mesh = false;                   ///< Once settled, "Make the mesh" and wait for it.
    double session_timeout_s = 600.0;         ///< Give up waiting for the session.
    /// The simulated operator turns the view every frame (measuring interaction), pixels.
    double orbit_px_per_frame = 0.0;
};

class HeadlessDriver {
public:
    HeadlessDriver(const HeadlessConfig& config, const AppState& app);

    bool headless() const { return config_.frames > 0; }
    /// How long the next frame may wait for input: an idle window sleeps (up to 50 ms, for
    /// live updates) once nothing is left to refine, so that capture and registration get
    /// the CPU; counted frames are drawn back to back.
    double idle_wait_s(bool view_complete) const;
    /// Before the panels are built: the operator's next action, as the buttons give it.
    void step(AppState& app, gui::UiActions& actions);
    /// This frame counts toward `frames`.
    bool counting() const { return phase_ == Phase::kCounting; }
    /// After the scene and the panels are drawn, before the swap: the screenshot of the
    /// last counted frame (the error names the file).
    Expected<void> after_draw(const FieldWindow& window) const;
    /// After the swap: counts the frame; an error when the session did not settle in time.
    Expected<void> end_frame();
    /// All frames counted.
    bool done() const { return headless() && counted_ >= config_.frames; }

private:
    enum class Phase { kCapturing, kSettling, kReregistering, kCounting };
    Phase drive_session(AppState& app, gui::UiActions& actions);
    bool device_steps(AppState& app, gui::UiActions& actions);

    HeadlessConfig config_;
    Phase phase_ = Phase::kCounting;
    int counted_ = 0;
    bool reregister_sent_ = false, connect_sent_ = false, settings_sent_ = false;
    bool mesh_sent_ = false;
    Stopwatch started_;
};

}  // namespace anascan::field
