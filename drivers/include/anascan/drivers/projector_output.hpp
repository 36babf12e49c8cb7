#pragma once
/// \file
/// Projector output: a GLFW full-screen window on a chosen monitor that shows 8-bit
/// patterns, as a PatternOutput (load, then show(i) returning when it is on screen) or as
/// a sequence calling back after each pattern is on screen (the camera captures there), so
/// projection and capture stay in step.

#include <chrono>
#include <cstdint>
#include <functional>
#include <memory>
#include <span>
#include <stop_token>
#include <string>
#include <vector>

#include "anascan/drivers/pattern_output.hpp"
#include "anascan/processing/core/expected.hpp"

namespace anascan::drivers {

struct MonitorInfo {
    std::string name;
    int width_px = 0;  ///< Current video mode.
    int height_px = 0;
    double refresh_hz = 0.0;
};

struct ProjectorConfig {
    int monitor_index =
        -1;  ///< Into monitors(); -1 = the last one (a projector is usually the second screen).
    bool fullscreen =
        true;  ///< false: a window of window_width_px x window_height_px (tests, preview).
    int window_width_px = 640;
    int window_height_px = 480;
    std::chrono::milliseconds settle{
        0};  ///< Wait after the buffer swap (projector latency) before the callback.
    bool keep_read_back = false;  ///< Read each drawn frame back (glReadPixels) for read_back().
};

/// Not thread-safe, and GLFW's rule applies: create, use and destroy it on the main thread.
/// Owns the GLFW window and context; destroying it closes the window.
class ProjectorOutput : public PatternOutput {
public:
    /// Monitors GLFW sees (empty without a display).
    static std::vector<MonitorInfo> monitors();
    /// Opens the window; kUnsupported without a display, kInvalidArgument for a monitor
    /// index out of range (the message lists the monitors).
    static Expected<std::unique_ptr<ProjectorOutput>> open(const ProjectorConfig& config);

    /// Loads the patterns, then shows them in order; after each is on screen (buffer
    /// swapped, GPU finished, `settle` waited) calls on_shown(index). on_shown returning
    /// false, or `stop`, ends the sequence with kCancelled. kInvalidArgument for a pattern
    /// of the wrong size.
    Expected<void> show_sequence(std::span<const Pattern> patterns,
                                 const std::function<bool(std::size_t index)>& on_shown,
                                 std::stop_token stop = {});
    /// The frame buffer of the pattern shown last, read with glReadPixels just before the
    /// swap (the front buffer cannot be read back on every driver, e.g. Mesa under Xvfb),
    /// 8-bit grey (red channel), row 0 at the top; empty unless keep_read_back is set.
    virtual Pattern read_back() const = 0;
};

}  // namespace anascan::drivers
