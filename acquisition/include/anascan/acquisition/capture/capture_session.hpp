#pragma once
/// \file
/// A running capture session: one thread per scanner captures on request, a persistence
/// thread saves each scan (and only then acknowledges it), and a registration worker places
/// the saved scans live and keeps the coverage up to date. Capture never waits for
/// registration: the worker's queue holds scans in memory up to a bound and, past it, only
/// their sequence numbers (the worker then reads them back from the session).
///
///   scanner thread --(bounded, scans)--> persistence --(seq [+ scan])--> registration
///
/// See docs/capture-session.md.

#include <chrono>
#include <cstdint>
#include <functional>
#include <future>
#include <memory>
#include <optional>
#include <string>

#include "anascan/acquisition/capture/device_control.hpp"
#include "anascan/acquisition/capture/session_events.hpp"
#include "anascan/acquisition/live/live_registration.hpp"
#include "anascan/acquisition/store/session_store.hpp"
#include "anascan/processing/core/expected.hpp"
#include "anascan/processing/core/pose.hpp"
#include "anascan/processing/coverage/coverage.hpp"

namespace anascan::drivers {
class Scanner;
}

namespace anascan::acquisition {

struct CaptureSessionConfig {
    /// Captured scans waiting to be saved; a full queue holds the scanner back (a scan not
    /// yet saved must not pile up in memory).
    std::size_t save_queue_capacity = 2;
    /// Saved scans handed to the registration worker with their points; beyond this only
    /// the sequence number is queued and the worker reads the scan back from disk.
    std::size_t registration_queue_capacity = 4;
    bool register_live = true;  ///< False: scans stay queued (registered later).
    bool coverage_live = true;  ///< Coverage after each registration.
    std::chrono::milliseconds capture_timeout{120000};
    LiveRegistrationConfig registration{};
    CoverageConfig coverage{};
    double coverage_voxel_size_m = 0.002;
    /// Background refine() calls in a row while no scan waits, at most (each has a budget).
    int max_background_steps = 50;  ///< Scans reduced for coverage (session_coverage).
};

/// Opens the scanner (again, after it was unplugged).
using ScannerOpener = std::function<Expected<std::unique_ptr<drivers::Scanner>>()>;

/// One capture asked for by the operator.
struct CaptureRequest {
    /// Runs on the scanner thread right before the capture: a simulated operator moves the
    /// scanner here. When it returns a transform, the device's pose of the scan is ground
    /// truth in the device's world frame and the transform takes it to the session's truth
    /// frame; the pose is then recorded as the true pose, not given to registration.
    std::function<std::optional<Pose>(drivers::Scanner&)> before;
    /// The operator turned the stone over before this scan.
    bool turned_over = false;
};

/// Receives events on the session's threads: must be thread-safe and quick.
using SessionEventSink = std::function<void(const SessionEvent&)>;

class CaptureSession {
public:
    /// Starts the persistence and registration threads on an open store. Scans already in
    /// the session and not excluded are registered again first (a resumed session).
    static Expected<std::unique_ptr<CaptureSession>> start(std::unique_ptr<SessionStore> store,
                                                           CaptureSessionConfig config,
                                                           SessionEventSink sink);
    /// Saves every scan already captured, finishes the registration in progress and stops.
    ~CaptureSession();
    CaptureSession(const CaptureSession&) = delete;
    CaptureSession& operator=(const CaptureSession&) = delete;

    /// Starts the scanner thread (one scanner per session for now); the device is opened
    /// on that thread at the first capture and again after it was unplugged.
    Expected<void> attach_scanner(std::string uri, ScannerOpener open);

    /// Queues a capture. The future resolves when the scan is acknowledged (its sequence
    /// number) or with the error that prevented it (the device's or the disk's).
    std::future<Expected<std::int64_t>> capture(CaptureRequest request);

    /// Waits until every saved scan has been decided and the background refinement and
    /// coverage have caught up.
    void wait_until_idle();

    /// Operator actions (recorded in the session, applied by the worker).
    Expected<void> exclude(std::int64_t seq, bool excluded);
    /// Registers a saved scan again, from its file, against the other registered scans
    /// (asynchronous: the result arrives as a registration event). Fails for an unknown or
    /// excluded scan.
    Expected<void> reregister(std::int64_t seq);
    Expected<void> add_note(std::optional<std::int64_t> seq, std::string_view text);

    SessionStore& store();

    /// The attached device's settings (opened first when it is not). Runs on the scanner
    /// thread between captures (capture_session_device.cpp).
    std::future<Expected<DeviceSettingsForm>> device_settings();
    /// Applies the form's values, validated by the device (kInvalidArgument naming the
    /// setting and its range; nothing changes then), keeps them for later openings (after
    /// an unplug) and records a "device-settings" session event; the settings now in
    /// effect. Later scans carry them in their settings_json.
    std::future<Expected<DeviceSettingsForm>> apply_device_settings(DeviceSettingsForm form);
    /// What the device's cameras see now (structured light: cam1 and cam2 under the
    /// projector's white), each at most `max_width_px` wide; no images for a scanner
    /// without cameras. Queued behind the captures asked for before.
    std::future<Expected<CameraPreview>> preview_cameras(int max_width_px);

private:
    struct Impl;
    explicit CaptureSession(std::unique_ptr<Impl> impl);
    std::unique_ptr<Impl> impl_;
};

}  // namespace anascan::acquisition
