#include "session_link.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cstdio>

#include "anascan/gui/session_view.hpp"
#include "future_ready.hpp"
#include "thread_priority.hpp"

namespace anascan::field {
namespace {

using acquisition::SessionEventKind;

}  // namespace

void EventQueue::push(acquisition::SessionEvent event) {
    std::lock_guard lock(mutex_);
    events_.push_back(std::move(event));
}

std::deque<acquisition::SessionEvent> EventQueue::take() {
    std::lock_guard lock(mutex_);
    return std::exchange(events_, {});
}

SessionLink::SessionLink(SessionLinkConfig config)
    : config_(std::move(config)),
      chunks_({.worker_nice = config_.worker_nice,
               .upload_points_per_frame = config_.upload_points_per_frame}),
      preview_(config_.worker_nice),
      mesh_(config_.worker_nice, config_.mesh_resolution_mm) {}

SessionLink::~SessionLink() = default;

// The UI reads through its own read-only connection even while the app captures: a
// WAL reader never waits for the session's writes (their commits fsync), whereas the
// capture session's store is shared with its threads under one mutex.
const acquisition::SessionStore* SessionLink::store() const {
    if (read_store_) return read_store_.get();
    return session_ ? &session_->store() : nullptr;
}

void SessionLink::open(gui::FieldViewState& view) {
    view.session_dir = config_.dir.string();
    if (std::filesystem::exists(config_.dir / "session.sqlite")) {
        open_store(view);
    } else {
        view.session_check = "new session: created at the first capture";
    }
    list_devices(view, active_device_uri());
}

void SessionLink::open_store(gui::FieldViewState& view) {
    auto store =
        acquisition::SessionStore::open(config_.dir, acquisition::SessionOpenMode::kReadOnly);
    if (!store) {
        view.status.last_error = store.error().message;
        return;
    }
    read_store_ = std::move(*store);
    pending_check_ = std::async(std::launch::async, [dir = config_.dir, n = config_.worker_nice] {
        lower_this_thread_priority(n);
        return acquisition::check_session(dir);
    });
}

/// The device asked for, else the one that took the session's newest scan (a capture adds
/// to the same stone, seen by the same scanner), else the default.
std::string SessionLink::active_device_uri() const {
    if (!config_.device_uri.empty()) return config_.device_uri;
    if (read_store_) {
        auto scans = read_store_->scans();
        if (scans && !scans->empty() && !scans->back().device_id.empty())
            return scans->back().device_id;
    }
    return kDefaultDeviceUri;
}

void SessionLink::list_devices(gui::FieldViewState& view, const std::string& uri) {
    for (const scanner_sources::ScannerListing& s : scanner_sources::list_scanners()) {
        view.device.devices.push_back({.id = s.uri,
                                       .kind = s.model,
                                       .connected = true,
                                       .status = s.simulated ? "simulated, ready" : "ready"});
    }
    auto active = std::find_if(view.device.devices.begin(), view.device.devices.end(),
                               [&](const gui::DeviceRow& d) { return d.id == uri; });
    if (active == view.device.devices.end()) {
        view.device.devices.push_back(
            {.id = uri, .kind = "scanner", .connected = true, .status = "ready"});
        active = view.device.devices.end() - 1;
    }
    view.device.active_device = static_cast<int>(active - view.device.devices.begin());
}

void SessionLink::poll(gui::FieldViewState& view, gui::PointRenderer& renderer) {
    drain_events(view);
    poll_futures(view);
    timed_refresh(view);
    if (dirty_) refresh(view, renderer);
    if (std::string error = chunks_.take_error(); !error.empty()) view.status.last_error = error;
    if (coverage_dirty_) refresh_coverage(view, renderer);
    if (chunks_.poll(store(), renderer)) dirty_ = true;  // the pose may have moved meanwhile
    preview_.poll(store(), view.device);
    device_.poll(device_inputs(), view.device);
    mesh_.poll(view.mesh, view.scans);
}

/// Once a second: another process may be capturing into the session (no events then), and
/// the free disk space.
void SessionLink::timed_refresh(gui::FieldViewState& view) {
    const auto now = std::chrono::steady_clock::now();
    if (now < next_timed_refresh_) return;
    if (!session_) dirty_ = coverage_dirty_ = true;
    std::error_code ec;
    const auto space = std::filesystem::space(
        std::filesystem::exists(config_.dir) ? config_.dir : config_.dir.parent_path(), ec);
    if (!ec) view.status.disk_free_bytes = space.available;
    next_timed_refresh_ = now + std::chrono::seconds(1);
}

void SessionLink::drain_events(gui::FieldViewState& view) {
    for (const acquisition::SessionEvent& event : events_->take()) {
        if (config_.log_events && !event.message.empty()) {
            std::printf("%s\n", event.message.c_str());
            std::fflush(stdout);
        }
        switch (event.kind) {
            case SessionEventKind::kRegistered:
            case SessionEventKind::kRegistrationFailed:
            case SessionEventKind::kRegistrationFlagged:
                reregistering_.erase(event.seq);  // its new result is in the row
                dirty_ = true;
                break;
            case SessionEventKind::kSaved:
            case SessionEventKind::kPosesRefined:
                dirty_ = true;
                break;
            case SessionEventKind::kCoverage:
                view.status.coverage_percent = event.coverage_fraction * 100.0;
                coverage_dirty_ = true;
                break;
            case SessionEventKind::kDeviceError:
                view.status.last_error = event.message;
                set_device_status(view, false, "error: " + event.message);
                break;
            case SessionEventKind::kDeviceBack:
                set_device_status(view, true, "back: " + event.message);
                break;
            case SessionEventKind::kDeviceWarning:
                set_device_status(view, true, "warning: " + event.message);
                break;
            case SessionEventKind::kSaveFailed:
                view.status.last_error = event.message;
                dirty_ = true;
                break;
        }
    }
}

void SessionLink::poll_capture(gui::FieldViewState& view) {
    if (!ready(pending_capture_)) return;
    const Expected<std::int64_t> acknowledged = pending_capture_->get();
    pending_capture_.reset();
    ++captures_finished_;
    dirty_ = true;
    if (acknowledged) {
        ++acknowledged_;
        view.capture_problem.reset();  // recovered: the banner goes
        set_device_status(view, true, "ready");
        return;
    }
    const Error& error = acknowledged.error();
    view.capture_problem = gui::capture_problem(error);
    view.status.last_error = view.capture_problem->line();
    if (error.code == ErrorCode::kDisconnected || error.code == ErrorCode::kTimeout)
        set_device_status(view, false, "unplugged or silent");
    else
        set_device_status(view, true, "ready; " + view.capture_problem->headline);
}

void SessionLink::poll_futures(gui::FieldViewState& view) {
    poll_capture(view);
    view.device.capturing = pending_capture_.has_value();
    if (ready(pending_check_)) {
        const auto report = pending_check_->get();
        pending_check_.reset();
        if (!report)
            view.session_check = "session check failed: " + report.error().message;
        else
            view.session_check = gui::check_summary(*report);
    }
    if (ready(pending_idle_)) {
        pending_idle_->get();
        pending_idle_.reset();
        dirty_ = coverage_dirty_ = true;
    }
}

void SessionLink::set_device_status(gui::FieldViewState& view, bool connected, std::string status) {
    const int i = view.device.active_device;
    if (i < 0 || i >= static_cast<int>(view.device.devices.size())) return;
    view.device.devices[static_cast<std::size_t>(i)].connected = connected;
    view.device.devices[static_cast<std::size_t>(i)].status = std::move(status);
}

void SessionLink::refresh(gui::FieldViewState& view, gui::PointRenderer& renderer) {
    dirty_ = false;
    if (store() == nullptr) return;
    auto scans = store()->scans();
    if (!scans) {
        view.status.last_error = scans.error().message;
        return;
    }
    view.scans.clear();
    view.status.queued_registrations = 0;
    for (const acquisition::ScanRecord& record : *scans) {
        preview_.saw_scan(record.seq);
        view.scans.push_back(gui::scan_row(record));
        gui::ScanRow& row = view.scans.back();
        if (reregistering_.contains(record.seq) && row.state != gui::ScanRowState::kExcluded) {
            row.state = gui::ScanRowState::kQueued;  // until its new result arrives
            row.message = "registering again";
        }
        if (row.state == gui::ScanRowState::kQueued) ++view.status.queued_registrations;
    }
    gui::mark_unjoined(view.scans);
    chunks_.update(*scans, renderer);
}

void SessionLink::refresh_coverage(gui::FieldViewState& view, gui::PointRenderer& renderer) {
    coverage_dirty_ = false;
    if (store() == nullptr) return;
    const auto json = store()->value("coverage");
    if (!json || !*json) return;
    // Unchanged: keep the markers (new markers would restart the view's refinement).
    if (**json == coverage_json_) return;
    coverage_json_ = **json;
    const gui::StoredCoverage coverage = gui::parse_coverage_json(**json);
    if (coverage.fraction) view.status.coverage_percent = *coverage.fraction * 100.0;
    renderer.set_hole_markers(coverage.holes);
}

bool SessionLink::settled() const {
    return !pending_capture_ && !pending_check_ && !pending_idle_ && !dirty_ &&
           reregistering_.empty() && chunks_.settled() && preview_.settled() && device_.settled() &&
           mesh_.settled();
}

bool SessionLink::busy(const gui::FieldViewState& view) const {
    return pending_capture_.has_value() || pending_idle_.has_value() ||
           view.status.queued_registrations > 0;
}

void SessionLink::request_idle() {
    if (!session_ || pending_idle_) return;
    pending_idle_ =
        std::async(std::launch::async, [session = session_.get()] { session->wait_until_idle(); });
}

}  // namespace anascan::field
