#include "session_link.hpp"

#include <fmt/format.h>

#include <algorithm>

#include "anascan/gui/session_view.hpp"
#include "thread_priority.hpp"

namespace anascan::field {
namespace {

using acquisition::SessionEventKind;

template <typename T>
bool ready(const std::optional<std::future<T>>& future) {
    return future && future->wait_for(std::chrono::seconds(0)) == std::future_status::ready;
}

}  // namespace

void EventQueue::push(acquisition::SessionEvent event) {
    std::lock_guard lock(mutex_);
    events_.push_back(std::move(event));
}

std::deque<acquisition::SessionEvent> EventQueue::take() {
    std::lock_guard lock(mutex_);
    return std::exchange(events_, {});
}

SessionLink::SessionLink(SessionLinkConfig config) : config_(std::move(config)) {}

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
    for (const scanner_sources::ScannerListing& s : scanner_sources::list_scanners()) {
        view.device.devices.push_back({.id = s.uri,
                                       .kind = s.model,
                                       .connected = true,
                                       .status = s.simulated ? "simulated, ready" : "ready"});
    }
    auto active = std::find_if(view.device.devices.begin(), view.device.devices.end(),
                               [&](const gui::DeviceRow& d) { return d.id == config_.device_uri; });
    if (active == view.device.devices.end()) {
        view.device.devices.push_back(
            {.id = config_.device_uri, .kind = "scanner", .connected = true, .status = "ready"});
        active = view.device.devices.end() - 1;
    }
    view.device.active_device = static_cast<int>(active - view.device.devices.begin());
    if (!std::filesystem::exists(config_.dir / "session.sqlite")) {
        view.session_check = "new session: created at the first capture";
        return;
    }
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

void SessionLink::poll(gui::FieldViewState& view, gui::PointRenderer& renderer) {
    drain_events(view);
    poll_futures(view);
    const auto now = std::chrono::steady_clock::now();
    if (now >= next_timed_refresh_) {
        // Another process may be capturing into the session (no events then): look again.
        if (!session_) dirty_ = coverage_dirty_ = true;
        std::error_code ec;
        const auto space = std::filesystem::space(
            std::filesystem::exists(config_.dir) ? config_.dir : config_.dir.parent_path(), ec);
        if (!ec) view.status.disk_free_bytes = space.available;
        next_timed_refresh_ = now + std::chrono::seconds(1);
    }
    if (dirty_) refresh(view, renderer);
    if (!load_error_.empty()) view.status.last_error = std::exchange(load_error_, {});
    if (coverage_dirty_) refresh_coverage(view, renderer);
    poll_load(renderer);
    poll_preview(view);
    poll_device(view);
}

/// The newest scan's preview, read and projected off the UI thread (its points are freed
/// there), uploaded here; a newer scan waits for the read in progress.
void SessionLink::poll_preview(gui::FieldViewState& view) {
    if (ready(pending_preview_)) {
        const Expected<gui::ScanPreview> preview = pending_preview_->get();
        pending_preview_.reset();
        if (preview) preview_texture_.show(*preview, view.device);
    }
    if (pending_preview_ || newest_seq_ <= preview_seq_ || store() == nullptr) return;
    preview_seq_ = newest_seq_;
    pending_preview_ = std::async(std::launch::async,
                                  [store = store(), seq = preview_seq_,
                                   n = config_.worker_nice]() -> Expected<gui::ScanPreview> {
                                      lower_this_thread_priority(n);
                                      auto scan = store->load_scan(seq);
                                      if (!scan) return fail(scan.error());
                                      return gui::make_scan_preview(*scan);
                                  });
}

void SessionLink::drain_events(gui::FieldViewState& view) {
    for (const acquisition::SessionEvent& event : events_->take()) {
        switch (event.kind) {
            case SessionEventKind::kRegistered:
            case SessionEventKind::kRegistrationFailed:
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
            case SessionEventKind::kSaveFailed:
                view.status.last_error = event.message;
                dirty_ = true;
                break;
        }
    }
}

void SessionLink::poll_futures(gui::FieldViewState& view) {
    if (ready(pending_capture_)) {
        const Expected<std::int64_t> acknowledged = pending_capture_->get();
        pending_capture_.reset();
        ++captures_finished_;
        if (acknowledged) {
            ++acknowledged_;
            view.capture_problem.reset();  // recovered: the banner goes
            set_device_status(view, true, "ready");
        } else {
            const Error& error = acknowledged.error();
            view.capture_problem = gui::capture_problem(error);
            view.status.last_error = view.capture_problem->line();
            if (error.code == ErrorCode::kDisconnected || error.code == ErrorCode::kTimeout)
                set_device_status(view, false, "unplugged or silent");
            else
                set_device_status(view, true, "ready; " + view.capture_problem->headline);
        }
        dirty_ = true;
    }
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
        newest_seq_ = std::max(newest_seq_, record.seq);
        view.scans.push_back(gui::scan_row(record));
        gui::ScanRow& row = view.scans.back();
        if (reregistering_.contains(record.seq) && row.state != gui::ScanRowState::kExcluded) {
            row.state = gui::ScanRowState::kQueued;  // until its new result arrives
            row.message = "registering again";
        }
        if (row.state == gui::ScanRowState::kQueued) ++view.status.queued_registrations;
    }
    update_chunks(*scans, renderer);
}

/// Registered scans of the model's group are drawn at their poses; others are removed.
void SessionLink::update_chunks(const std::vector<acquisition::ScanRecord>& scans,
                                gui::PointRenderer& renderer) {
    const int group = gui::model_group(scans);
    std::map<std::int64_t, Pose>& wanted = wanted_;
    wanted.clear();
    for (const auto& record : scans)
        if (gui::drawn_in_view(record, group)) wanted.emplace(record.seq, *record.pose);
    for (auto it = shown_.begin(); it != shown_.end();) {
        const auto w = wanted.find(it->first);
        if (w == wanted.end()) {
            renderer.remove_chunk(it->first);
            it = shown_.erase(it);
            continue;
        }
        if (!w->second.isApprox(it->second, 1e-12)) {
            renderer.set_pose(it->first, w->second);
            it->second = w->second;
        }
        ++it;
    }
    to_load_.clear();
    for (const auto& [seq, pose] : wanted)
        if (!shown_.contains(seq) && seq != loading_seq_ && !unloadable_.contains(seq))
            to_load_.push_back(seq);
}

/// One scan read at a time, off the UI thread; its points go to the renderer (the only
/// copy) and the cloud is freed.
void SessionLink::poll_load(gui::PointRenderer& renderer) {
    uploaded_in_last_poll_ = uploading_;  // a step below
    const auto started = std::chrono::steady_clock::now();
    if (ready(pending_load_)) {
        Expected<Scan> scan = pending_load_->get();
        pending_load_.reset();
        const std::int64_t seq = std::exchange(loading_seq_, -1);
        const auto wanted = wanted_.find(seq);
        if (scan && wanted != wanted_.end()) {
            // Shuffled on the load thread; uploaded over the next frames (upload_step): 20 000
            // points a frame are 240 kB of positions and 60 kB of colours.
            const std::size_t step = config_.upload_points_per_frame;
            renderer.add_chunk(seq, std::move(scan->cloud), wanted->second,
                               {.shuffled = step > 0, .points_per_step = step});
            uploaded_in_last_poll_ = true;
            shown_[seq] = wanted->second;
        } else if (!scan) {
            load_error_ = scan.error().message;
            unloadable_.insert(seq);
        }
        dirty_ = true;  // the pose may have moved meanwhile; the row may have gone
    }
    uploading_ = renderer.upload_step();
    if (uploaded_in_last_poll_)
        upload_work_ms_.push_back(
            std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - started)
                .count());
    // One scan's points in CPU memory at a time: the next is read once this one is uploaded.
    if (pending_load_ || uploading_ || to_load_.empty() || store() == nullptr) return;
    loading_seq_ = to_load_.front();
    to_load_.erase(to_load_.begin());
    pending_load_ = std::async(std::launch::async,
                               [store = store(), seq = loading_seq_, n = config_.worker_nice,
                                shuffle = config_.upload_points_per_frame > 0] {
                                   lower_this_thread_priority(n);
                                   auto scan = store->load_scan(seq);
                                   if (scan && shuffle) gui::shuffle_chunk_points(scan->cloud, seq);
                                   return scan;
                               });
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
    return !pending_capture_ && !pending_load_ && !uploading_ && !pending_check_ &&
           !pending_idle_ && !dirty_ && to_load_.empty() && reregistering_.empty() &&
           !pending_preview_ && newest_seq_ <= preview_seq_ && !pending_settings_ &&
           !(cameras_wanted_ && cameras_due_);
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
