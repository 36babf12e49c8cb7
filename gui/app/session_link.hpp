#pragma once
/// \file
/// The field app attached to a capture session (acquisition only). Viewing opens the store
/// read-only (it works alongside an `anascan capture` that holds the session); the first
/// capture opens it for writing and runs a CaptureSession inside the app. Session events
/// arrive on acquisition's threads and go into a queue that the UI thread drains each frame;
/// captures, scan loads, the crash check and "wait until idle" are futures the UI polls, so
/// the UI thread never waits for capture, registration or disk.

#include <chrono>
#include <cstdint>
#include <deque>
#include <filesystem>
#include <future>
#include <map>
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
#include "anascan/gui/scan_preview.hpp"
#include "anascan/gui/ui_action.hpp"
#include "anascan/scanner_sources/scanner_source.hpp"
#include "preview_texture.hpp"

namespace anascan::field {

struct SessionLinkConfig {
    std::filesystem::path dir;
    std::string device_uri = "sim:structured-light/small-block";  ///< Active at start.
    scanner_sources::SimulatedTour tour;                          ///< For simulated scanners.
    scanner_sources::ScannerSettings settings;
    int sim_unplug_after = -1;  ///< Fault injection (simulated scanners), -1: never.
    /// Nice increment of the capture session's threads and the scan loads over the UI
    /// thread (thread_priority.hpp); 0: same priority.
    int worker_nice = 10;
    /// A loaded scan's points go to the GPU in steps of this many a frame (glBufferSubData),
    /// shuffled on the load thread; 0: shuffled and uploaded in one frame.
    std::size_t upload_points_per_frame = 20'000;
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
    bool uploaded_in_last_poll() const { return uploaded_in_last_poll_; }
    /// Time each uploading poll spent taking the loaded scan and copying points, ms.
    const std::vector<double>& upload_work_ms() const { return upload_work_ms_; }
    std::size_t shown_scans() const { return shown_.size(); }

private:
    const acquisition::SessionStore* store() const;
    bool start_session(gui::FieldViewState& view);
    void capture(gui::FieldViewState& view);
    bool attach(const std::string& uri, gui::FieldViewState& view);
    void set_excluded(std::int64_t seq, bool excluded, gui::FieldViewState& view);
    void reregister(std::int64_t seq, gui::FieldViewState& view);
    void drain_events(gui::FieldViewState& view);
    void poll_futures(gui::FieldViewState& view);
    void refresh(gui::FieldViewState& view, gui::PointRenderer& renderer);
    void update_chunks(const std::vector<acquisition::ScanRecord>& scans,
                       gui::PointRenderer& renderer);
    void poll_load(gui::PointRenderer& renderer);
    void poll_preview(gui::FieldViewState& view);
    void refresh_coverage(gui::FieldViewState& view, gui::PointRenderer& renderer);
    void set_device_status(gui::FieldViewState& view, bool connected, std::string status);
    // The device panel's device (session_link_device.cpp).
    void open_device(gui::FieldViewState& view);
    void apply_settings(gui::FieldViewState& view);
    void poll_device(gui::FieldViewState& view);
    void take_settings(gui::DevicePanelState& device);
    void poll_cameras(gui::DevicePanelState& device);

    SessionLinkConfig config_;
    std::shared_ptr<EventQueue> events_ = std::make_shared<EventQueue>();
    std::unique_ptr<acquisition::SessionStore> read_store_;
    std::unique_ptr<acquisition::CaptureSession> session_;
    std::string attached_uri_;
    int acknowledged_ = 0;  ///< Scans in the session: the tour's next view.
    int captures_finished_ = 0;
    bool turned_over_pending_ = false;
    bool dirty_ = true, coverage_dirty_ = true;
    std::chrono::steady_clock::time_point next_timed_refresh_{};
    std::map<std::int64_t, Pose> shown_;    ///< Chunks in the renderer and their poses.
    std::map<std::int64_t, Pose> wanted_;   ///< Scans the view should show, at these poses.
    std::vector<std::int64_t> to_load_;     ///< Registered scans whose points are not shown yet.
    std::set<std::int64_t> unloadable_;     ///< Scans whose file could not be read.
    std::set<std::int64_t> reregistering_;  ///< Asked to register again, no result yet.
    std::string load_error_;                ///< For the status bar.
    std::string coverage_json_;             ///< The stored coverage last shown.
    std::int64_t newest_seq_ = -1;          ///< The newest scan in the session.
    std::int64_t preview_seq_ = -1;         ///< The scan previewed (or being read for it).
    PreviewTexture preview_texture_;
    CameraTextures camera_textures_;
    bool settings_applying_ = false;  ///< pending_settings_ is an apply (not a read).
    bool cameras_wanted_ = false;     ///< The device has cameras (until a preview says none).
    bool cameras_due_ = false;        ///< No preview since the device was attached or captured.
    int captures_seen_ = 0;
    std::chrono::steady_clock::time_point next_camera_grab_{};
    // Futures last: destroyed (and waited for) before the session they use.
    std::optional<std::future<Expected<std::int64_t>>> pending_capture_;
    std::optional<std::future<Expected<Scan>>> pending_load_;
    std::int64_t loading_seq_ = -1;
    bool uploading_ = false;  ///< The renderer is still uploading a loaded scan.
    bool uploaded_in_last_poll_ = false;
    std::vector<double> upload_work_ms_;
    std::optional<std::future<Expected<acquisition::SessionCheckReport>>> pending_check_;
    std::optional<std::future<Expected<gui::ScanPreview>>> pending_preview_;
    std::optional<std::future<void>> pending_idle_;
    std::optional<std::future<Expected<acquisition::DeviceSettingsForm>>> pending_settings_;
    std::optional<std::future<Expected<acquisition::CameraPreview>>> pending_cameras_;
};

}  // namespace anascan::field
