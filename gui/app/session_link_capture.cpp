// The operator's session actions: capture (a CaptureSession inside the app, started at the
// first capture), exclude / include, turned over, choosing the device.
#include <fmt/format.h>

#include "session_link.hpp"
#include "thread_priority.hpp"

namespace anascan::field {

/// Opens the session for writing and starts the capture session; says clearly when another
/// process holds it or the folder cannot be written.
bool SessionLink::start_session(gui::FieldViewState& view) {
    auto store =
        acquisition::SessionStore::open(config_.dir, acquisition::SessionOpenMode::kCreateOrOpen);
    if (!store) {
        const bool held = store.error().code == ErrorCode::kBusy;
        view.status.last_error =
            held ? fmt::format(
                       "session {} is held by another process (an `anascan capture` "
                       "running?): capture there, or close it and capture again here",
                       config_.dir.string())
                 : fmt::format("cannot open session {} for capture: {}", config_.dir.string(),
                               store.error().message);
        view.capture_problem = gui::CaptureProblem{
            .headline = held ? "session held by another process" : "cannot open the session",
            .details = view.status.last_error,
            .what_to_try = held ? "Stop the other capture, then capture again here."
                                : "Restart the app with --session on a writable folder."};
        return false;
    }
    if (auto scans = (*store)->scans(); scans) acknowledged_ = static_cast<int>(scans->size());
    auto queue = events_;
    // Started from a lowered thread: its threads inherit the lower priority.
    auto session = call_at_lower_priority(config_.worker_nice, [&] {
        return acquisition::CaptureSession::start(
            std::move(*store), {},
            [queue](const acquisition::SessionEvent& event) { queue->push(event); });
    });
    if (!session) {
        view.status.last_error = "cannot start the capture session: " + session.error().message;
        return false;
    }
    session_ = std::move(*session);
    if (!read_store_) {  // a new session: the UI's own reader (see store())
        auto reader =
            acquisition::SessionStore::open(config_.dir, acquisition::SessionOpenMode::kReadOnly);
        if (reader) read_store_ = std::move(*reader);
    }
    view.session_check.clear();
    dirty_ = coverage_dirty_ = true;
    return true;
}

/// The scanner is attached at the first capture; one scanner per session.
bool SessionLink::attach(const std::string& uri, gui::FieldViewState& view) {
    if (attached_uri_ == uri) return true;
    if (!attached_uri_.empty()) {
        view.status.last_error =
            fmt::format("this session captures with {} (one scanner per session): choose it again",
                        attached_uri_);
        return false;
    }
    const scanner_sources::ScannerSource source{
        .uri = uri, .settings = config_.settings, .sim_unplug_after = config_.sim_unplug_after};
    auto ok = call_at_lower_priority(config_.worker_nice, [&] {
        return session_->attach_scanner(uri, scanner_sources::make_scanner_opener(source));
    });
    if (!ok) {
        view.status.last_error = ok.error().message;
        return false;
    }
    attached_uri_ = uri;
    return true;
}

void SessionLink::capture(gui::FieldViewState& view) {
    if (pending_capture_) return;
    const int device = view.device.active_device;
    if (device < 0 || device >= static_cast<int>(view.device.devices.size())) {
        view.status.last_error = "no device chosen: pick one in the device panel";
        ++captures_finished_;
        return;
    }
    const std::string uri = view.device.devices[static_cast<std::size_t>(device)].id;
    if ((!session_ && !start_session(view)) || !attach(uri, view)) {
        ++captures_finished_;  // finished, with the error in the status bar
        return;
    }
    acquisition::CaptureRequest request;
    if (scanner_sources::is_simulated(uri))
        request = scanner_sources::tour_request(config_.tour, acknowledged_);
    request.turned_over = request.turned_over || std::exchange(turned_over_pending_, false);
    pending_capture_ = session_->capture(std::move(request));
    view.device.capturing = true;
    set_device_status(view, true, "capturing");
}

void SessionLink::set_excluded(std::int64_t seq, bool excluded, gui::FieldViewState& view) {
    if (seq < 0) return;
    Expected<void> done;
    if (session_) {
        done = session_->exclude(seq, excluded);
    } else {
        // Viewing only: a small edit alongside whoever holds the session.
        auto store =
            acquisition::SessionStore::open(config_.dir, acquisition::SessionOpenMode::kEdit);
        done = store ? (*store)->set_excluded(seq, excluded) : fail(store.error());
    }
    if (!done) view.status.last_error = done.error().message;
    dirty_ = true;
}

/// Registers a saved scan again (CaptureSession::reregister, asynchronous: the row changes
/// when its registration event arrives). A session only viewed so far is opened for
/// capture first, as by the capture action.
void SessionLink::reregister(std::int64_t seq, gui::FieldViewState& view) {
    if (seq < 0) return;
    if (!session_ && !start_session(view)) return;
    if (auto ok = session_->reregister(seq); !ok) {
        view.status.last_error = "re-register: " + ok.error().message;
        return;
    }
    view.status.last_error.clear();
    reregistering_.insert(seq);
    dirty_ = true;
}

/// Opens the session for capture (if it is not) and attaches the active device; its
/// settings are then read by the device link.
void SessionLink::open_device(gui::FieldViewState& view) {
    const int device = view.device.active_device;
    if (device < 0 || device >= static_cast<int>(view.device.devices.size())) {
        view.status.last_error = "no device chosen: pick one in the device panel";
        return;
    }
    if (!session_ && !start_session(view)) return;
    (void)attach(view.device.devices[static_cast<std::size_t>(device)].id, view);
}

DeviceLinkInputs SessionLink::device_inputs() const {
    return {.session = session_.get(),
            .attached = !attached_uri_.empty(),
            .capturing = pending_capture_.has_value(),
            .captures_finished = captures_finished_};
}

bool SessionLink::apply(const gui::UiAction& action, gui::FieldViewState& view) {
    switch (action.kind) {
        case gui::UiActionKind::kCapture:
            capture(view);
            return true;
        case gui::UiActionKind::kExclude:
            set_excluded(action.seq, true, view);
            return true;
        case gui::UiActionKind::kInclude:
            set_excluded(action.seq, false, view);
            return true;
        case gui::UiActionKind::kTurnedOver:
            turned_over_pending_ = true;
            return true;
        case gui::UiActionKind::kReRegister:
            reregister(action.seq, view);
            return true;
        case gui::UiActionKind::kOpenDevice:
            open_device(view);
            return true;
        case gui::UiActionKind::kMakeMesh:
            mesh_.start(store(), view.mesh);
            return true;
        case gui::UiActionKind::kApplySettings:
            device_.apply_settings(device_inputs(), view.device.settings);
            return true;
        case gui::UiActionKind::kConnectDevice:
            if (action.device_index >= 0 &&
                action.device_index < static_cast<int>(view.device.devices.size()))
                view.device.active_device = action.device_index;
            return true;
        default:
            return false;
    }
}

}  // namespace anascan::field
