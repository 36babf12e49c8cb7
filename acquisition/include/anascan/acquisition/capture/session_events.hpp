#pragma once
/// \file
/// What a capture session tells the operator as it happens (printed by `anascan capture`,
/// shown by the field app).

#include <cstdint>
#include <string>
#include <string_view>

namespace anascan::acquisition {

enum class SessionEventKind {
    kSaved,               ///< A scan is durable and recorded: acknowledged.
    kSaveFailed,          ///< A captured scan could not be saved (disk full, read-only...).
    kRegistered,          ///< A scan was placed in a group.
    kRegistrationFailed,  ///< A scan could not be placed (state failed).
    /// A registered scan contradicts its group and was taken out (state flagged).
    kRegistrationFlagged,
    kPosesRefined,  ///< Background refinement or a group merge moved some poses.
    kCoverage,      ///< Coverage was recomputed.
    kDeviceError,   ///< A capture failed (unplugged, timeout, invalid setting).
    kDeviceBack,    ///< The device could be opened again after an error.
    /// A capture survived a device fault (unreadable frames dropped): the scan is good, the
    /// message says what the device did.
    kDeviceWarning,
};

/// Short name ("saved", "registration-failed", ...), for logs and the events table.
std::string_view to_string(SessionEventKind kind);

/// One event; the figures that do not apply to its kind are left at their defaults.
struct SessionEvent {
    SessionEventKind kind = SessionEventKind::kSaved;
    std::int64_t seq = -1;  ///< The scan it is about; -1 when none.
    std::string device;     ///< Device URI when it is about a device.
    std::string message;    ///< One line for the operator, with units.
    int group = -1;
    std::string method;  ///< How a scan was registered ("motion-prior", "global", ...).
    double rms_m = 0.0;
    double overlap_fraction = 0.0;
    double latency_s = 0.0;  ///< Acknowledgement to registered.
    double coverage_fraction = 0.0;
    std::size_t count = 0;  ///< Points of a saved scan, poses moved, holes of a coverage.
};

}  // namespace anascan::acquisition
