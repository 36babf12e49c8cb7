#pragma once
/// \file
/// A scanner: one call, one scan, with progress and cancellation.

#include <chrono>
#include <functional>
#include <stop_token>
#include <string>
#include <vector>

#include "anascan/drivers/device.hpp"
#include "anascan/drivers/frame.hpp"
#include "anascan/processing/core/scan.hpp"

namespace anascan::drivers {

/// Progress of a capture: fraction done and the stage ("projecting pattern 12/44").
struct CaptureProgress {
    double fraction = 0.0;  ///< 0..1.
    std::string stage;
};

/// How capture_scan reports and can be stopped.
struct CaptureControl {
    std::function<void(const CaptureProgress&)> on_progress;  ///< May be empty.
    std::stop_token stop;                                     ///< Request → kCancelled.
    std::chrono::milliseconds timeout{30000};                 ///< Whole capture.
    /// A fault the capture survived (unreadable frames dropped), one line naming the device
    /// part, called on the capture's thread once the capture ends. May be empty.
    std::function<void(const std::string&)> on_warning;
};

/// Not thread-safe: capture_scan runs on the caller's thread; another thread may only
/// request a stop through CaptureControl::stop.
class Scanner : public Device {
public:
    Scanner* as_scanner() override { return this; }

    /// One scan in the sensor frame with meta.sensor_origin_scan_m, device id and kind,
    /// settings_json and (when the device knows it) meta.T_world_scan.
    virtual Expected<Scan> capture_scan(const CaptureControl& control) = 0;

    /// What the scanner's cameras see now, one grey8 frame per camera (structured light:
    /// cam1, cam2 under the projector's full light), for the operator's live preview
    /// between captures; none for a scanner without cameras. Same thread as capture_scan.
    virtual Expected<std::vector<Frame>> preview_frames(std::chrono::milliseconds timeout) {
        (void)timeout;
        return std::vector<Frame>{};
    }
};

}  // namespace anascan::drivers
