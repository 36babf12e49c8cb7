#pragma once
// The threads and queues behind CaptureSession (capture_session.hpp).

#include <atomic>
#include <chrono>
#include <condition_variable>
#include <map>
#include <memory>
#include <mutex>
#include <thread>

#include "anascan/acquisition/capture/bounded_queue.hpp"
#include "anascan/acquisition/capture/capture_session.hpp"
#include "anascan/acquisition/coverage/session_coverage.hpp"
#include "anascan/drivers/scanner.hpp"

namespace anascan::acquisition {

/// A capture the operator asked for, until the scanner thread takes it.
struct PendingCapture {
    CaptureRequest request;
    std::promise<Expected<std::int64_t>> acknowledged;
    /// Instead of a capture (settings, preview): runs with the open scanner or the error
    /// that kept it from opening (capture_session_device.cpp).
    std::function<void(Expected<drivers::Scanner*>)> device_task;
};

/// A captured scan until it is saved.
struct CapturedScan {
    Scan scan;
    std::optional<Pose> true_pose;
    bool turned_over = false;
    std::promise<Expected<std::int64_t>> acknowledged;
};

/// A saved scan for the registration worker; without points past the queue's bound.
struct SavedScan {
    std::int64_t seq = 0;
    std::shared_ptr<const Scan> scan;  ///< Empty: read it back from the session.
    bool turned_over = false;
    std::chrono::system_clock::time_point acknowledged_at{};
    bool resumed = false;                      ///< Registered again after the session was reopened.
    std::optional<double> previous_latency_s;  ///< Of a resumed scan.
    int exclude_change = 0;   ///< Operator action instead of a scan: +1 exclude, -1 include.
    bool reregister = false;  ///< Operator action: register this saved scan again.
};

struct CaptureSession::Impl {
    Impl(std::unique_ptr<SessionStore> store_in, CaptureSessionConfig config_in,
         SessionEventSink sink_in);

    void emit(SessionEvent event);
    /// Work counted from a request until its scan is decided (or failed); wait_until_idle
    /// waits for zero.
    void begin_work();
    void end_work();

    // Scanner thread (capture_session.cpp).
    void scanner_loop(std::stop_token stop);
    Expected<CapturedScan> capture_one(PendingCapture& pending, std::stop_token stop);
    /// Opens the scanner when it is not open, with the operator's applied settings.
    Expected<void> open_if_needed();
    /// Refuses what no real scan is: no finite point, or the previous scan's points again.
    Expected<void> check_delivered(const Scan& scan);
    /// A failed capture: stored as a device-error event and announced.
    void report_device_error(const Error& error);
    void run_device_task(PendingCapture& pending);
    // Persistence thread (capture_session_save.cpp).
    void save_loop();
    void save_one(CapturedScan captured);
    // Registration worker (capture_session_register.cpp).
    void registration_loop();
    void register_one(const SavedScan& saved);
    /// Stores a decision of the registrar and reports it.
    void record_decision(const SavedScan& saved, const LiveDecision& decision);
    /// One refine() call; true when it still found work (call again).
    /// One refine() round; `interruptible`: it stops early for a waiting scan.
    bool refine_in_background(bool interruptible = true);
    /// After a scan of a reopened session: the background work a live session would have
    /// done before the next scan, so a replay decides like the capture did (the session's
    /// RMS gate comes from the links; without them look-alikes pass).
    void settle_after_replayed_scan();
    void update_coverage();
    /// Stores and announces the scans the registrar took out of their groups (state flagged).
    void record_taken_out(const std::vector<LiveTakenOut>& taken_out);
    void queue_for_registration(SavedScan saved);
    void requeue_session_scans();

    std::unique_ptr<SessionStore> store;
    const CaptureSessionConfig config;
    const SessionEventSink sink;

    std::string scanner_uri;
    ScannerOpener open_scanner;
    std::unique_ptr<drivers::Scanner> scanner;  ///< Scanner thread only.
    bool scanner_failed = false;                ///< Last capture failed: say when it is back.
    /// Digest of the last delivered scan's points: the same points twice is a frozen device.
    std::optional<std::uint64_t> last_scan_digest;
    /// Settings the operator applied: again at every opening (scanner thread only).
    std::optional<drivers::DeviceSettings> applied_settings;

    BoundedQueue<std::shared_ptr<PendingCapture>> requests{64};
    BoundedQueue<std::shared_ptr<CapturedScan>> to_save;
    BoundedQueue<SavedScan> to_register{1 << 20};
    std::atomic<std::size_t> registration_items_with_points{0};

    LiveRegistrar registrar;                               ///< Registration worker only.
    bool refine_due = false;                               ///< Registration worker only.
    bool coverage_due = false;                             ///< Registration worker only.
    std::map<std::int64_t, CoverageCopy> coverage_copies;  ///< Registration worker only.

    std::mutex work_mutex;
    std::condition_variable work_done;
    std::size_t work_in_flight = 0;

    std::jthread scanner_thread, save_thread, registration_thread;
};

}  // namespace anascan::acquisition
