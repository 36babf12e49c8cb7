#pragma once
/// \file
/// The field app attached to a capture session (acquisition only). Viewing opens the store
/// read-only (it works alongside an `anascan capture` that holds the session); the first
/// capture opens it for writing and runs a CaptureSession inside the app. Session events
/// arrive on acquisition's threads and go into a queue that the UI thread drains each frame;
/// captures, scan loads, the crash check and "wait until idle" are futures the UI polls, so
/// the UI thread never waits for capture, registration or disk. Its parts, by concern: the
/// scans' points in the renderer (ScanChunks), the newest scan's picture (LastScanPreview)
/// the attached device's settings and cameras (DeviceLink) and the fragment model the
/// operator asked for (MeshMaker); the link itself holds the
/// session, the operator's actions and the rows.

#include <chrono>
#include <cstdint>
#include <deque>
#include <filesystem>
#include <future>
#include <memory>
#include <mutex>
#include <optional>
#include <set>
#include <string>
#include <vector>

#include "anascan/acquisition/capture/capture_session.hpp"
#include "anascan/acquisition/store/session_check.hpp"
#include "anascan/gui/field_view_state.hpp"
#include "anascan/gui/point_renderer.hpp"
#include "anascan/gui/ui_action.hpp"
#include "anascan/scanner_sources/scanner_source.hpp"
#include "device_link.hpp"
#include "last_scan_preview.hpp"
#include "mesh_maker.hpp"
#include "scan_chunks.hpp"

namespace anascan::field {

/// The device of a new session when none is asked for.
inline constexpr const char* kDefaultDeviceUri = "sim:structured-light/small-block";

struct SessionLinkConfig {
    std::filesystem::path dir;
    /// Active at start; empty: the device of the session's newest scan, else
    /// kDefaultDeviceUri.
    std::string device_uri;
    scanner_sources::SimulatedTour tour;  ///< For simulated scanners.
    scanner_sources::ScannerSettings settings;
    int sim_unplug_after = -1;  ///< Fault injection (simulated scanners), -1: never.
    /// Nice increment of the capture session's threads and the scan loads over the UI
    /// thread (thread_priority.hpp); 0: same priority.
    int worker_nice = 10;
    /// A loaded scan's points go to the GPU in steps of this many a frame (glBufferSubData),
    /// shuffled on the load thread; 0: shuffled and uploaded in one frame.
    std::size_t upload_points_per_frame = 20'000;
    double mesh_resolution_mm = 1.0;  ///< The mesh view's resolution.
    /// Each session event's message on stdout as it is drained (a terminal log beside the
    /// window; "saved scan N" is printed once the scan is acknowledged).
    bool log_events = false;
};

/// Session events, pushed by acquisition's threads, drained by the UI thread.
class EventQueue {
public:
    void push(acquisition::SessionEvent event);
    std::deque<acquisition::SessionEvent> take();

private:
    std::mutex mutex_;
    std::deque<acquisition::SessionEvent> events_;
};

class SessionLink {
public:
    explicit SessionLink(SessionLinkConfig config);
    /// Saves what was captured and finishes the registration in progress (CaptureSession).
    ~SessionLink();
    SessionLink(const SessionLink&) = delete;
    SessionLink& operator=(const SessionLink&) = delete;

    /// Opens the session read-only when the folder exists (else it is created at the first
    /// capture), starts the crash check and lists the devices.
    void open(gui::FieldViewState& view);
    /// Once per frame on the UI thread: events, finished futures, scan rows, the points of
    /// newly registered scans, moved poses, coverage and free disk. Never blocks.
    void poll(gui::FieldViewState& view, gui::PointRenderer& renderer);
    /// Session actions (capture, exclude, include, re-register, turned over, device);
    /// false for others.
    bool apply(const gui::UiAction& action, gui::FieldViewState& view);

    /// Starts waiting (on another thread) until registration has caught up.
    void request_idle();
    /// Nothing pending: no capture, load, check or wait; rows up to date; idle reached
    /// when it was requested.
    bool settled() const;
    /// Registration or a capture in progress (for the frame-time report).
    bool busy(const gui::FieldViewState& view) const;
    int captures_finished() const { return captures_finished_; }
    bool capturing() const { return pending_capture_.has_value(); }
    /// The last poll() copied points to the GPU (a new scan, or a step of it).
    bool uploaded_in_last_poll() const { return chunks_.uploaded_in_last_poll(); }
    /// Time each uploading poll spent taking the loaded scan and copying points, ms.
    const std::vector<double>& upload_work_ms() const { return chunks_.upload_work_ms(); }
    std::size_t shown_scans() const { return chunks_.shown(); }
    /// The mesh the operator asked for, once it is made (once; then nothing until the next).
    std::optional<Mesh> take_mesh() { return mesh_.take_mesh(); }

private:
    const acquisition::SessionStore* store() const;
    void open_store(gui::FieldViewState& view);
    std::string active_device_uri() const;
    void list_devices(gui::FieldViewState& view, const std::string& uri);
    bool start_session(gui::FieldViewState& view);
    void capture(gui::FieldViewState& view);
    bool attach(const std::string& uri, gui::FieldViewState& view);
    void set_excluded(std::int64_t seq, bool excluded, gui::FieldViewState& view);
    void reregister(std::int64_t seq, gui::FieldViewState& view);
    void open_device(gui::FieldViewState& view);
    DeviceLinkInputs device_inputs() const;
    void drain_events(gui::FieldViewState& view);
    void poll_capture(gui::FieldViewState& view);
    void poll_futures(gui::FieldViewState& view);
    void timed_refresh(gui::FieldViewState& view);
    void refresh(gui::FieldViewState& view, gui::PointRenderer& renderer);
    void refresh_coverage(gui::FieldViewState& view, gui::PointRenderer& renderer);
    void set_device_status(gui::FieldViewState& view, bool connected, std::string status);

    SessionLinkConfig config_;
    std::shared_ptr<EventQueue> events_ = std::make_shared<EventQueue>();
    // The session: the UI's reader, and the capture session once the app captures.
    std::unique_ptr<acquisition::SessionStore> read_store_;
    std::unique_ptr<acquisition::CaptureSession> session_;
    std::string attached_uri_;
    // The operator's actions.
    int acknowledged_ = 0;  ///< Scans in the session: the tour's next view.
    int captures_finished_ = 0;
    bool turned_over_pending_ = false;
    std::set<std::int64_t> reregistering_;  ///< Asked to register again, no result yet.
    // What the view shows, and when to read it again.
    bool dirty_ = true, coverage_dirty_ = true;
    std::chrono::steady_clock::time_point next_timed_refresh_{};
    std::string coverage_json_;  ///< The stored coverage last shown.
    // The parts below run futures on the session: destroyed (and waited for) before it.
    ScanChunks chunks_;
    LastScanPreview preview_;
    DeviceLink device_;
    MeshMaker mesh_;
    std::optional<std::future<Expected<std::int64_t>>> pending_capture_;
    std::optional<std::future<Expected<acquisition::SessionCheckReport>>> pending_check_;
    std::optional<std::future<void>> pending_idle_;
};

}  // namespace anascan::field
