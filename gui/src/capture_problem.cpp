#include <string_view>

#include "anascan/gui/session_view.hpp"

namespace anascan::gui {
namespace {

bool contains(std::string_view text, std::string_view part) {
    return text.find(part) != std::string_view::npos;
}

}  // namespace

CaptureProblem capture_problem(const Error& error) {
    const std::string& cause = error.message;
    if (error.code == ErrorCode::kDisconnected || error.code == ErrorCode::kTimeout) {
        return {.headline = "capture failed: device unplugged or silent",
                .details = cause + " (unplugged or silent: plug it in, then capture again)",
                .what_to_try =
                    "Check the device's cable and power, then capture again: the "
                    "app opens the device again. Scans saved before are safe."};
    }
    // acquisition's advice for ENOSPC / EFBIG ("The disk is full: ...").
    if (contains(cause, "disk is full") || contains(cause, "No space left") ||
        contains(cause, "File too large")) {
        return {.headline = "DISK FULL: the scan was NOT saved",
                .details = cause,
                .what_to_try =
                    "Free space on the session's disk (or restart the app on a "
                    "session folder on another disk), then capture again. Scans "
                    "saved before are safe."};
    }
    if (contains(cause, "not writable") || contains(cause, "Permission denied") ||
        contains(cause, "Read-only")) {
        return {.headline = "the session folder cannot be written",
                .details = cause,
                .what_to_try =
                    "Fix the folder's permissions or restart the app on another "
                    "session folder, then capture again."};
    }
    return {.headline = "capture failed",
            .details = cause,
            .what_to_try = "Capture again; if it fails again, restart the device."};
}

}  // namespace anascan::gui
