#include "anascan/acquisition/capture/capture_session.hpp"

#include "capture/impl.hpp"

namespace anascan::acquisition {

std::string_view to_string(SessionEventKind kind) {
    switch (kind) {
        case SessionEventKind::kSaved:
            return "saved";
        case SessionEventKind::kSaveFailed:
            return "save-failed";
        case SessionEventKind::kRegistered:
            return "registered";
        case SessionEventKind::kRegistrationFailed:
            return "registration-failed";
        case SessionEventKind::kRegistrationFlagged:
            return "registration-flagged";
        case SessionEventKind::kPosesRefined:
            return "poses-refined";
        case SessionEventKind::kCoverage:
            return "coverage";
        case SessionEventKind::kDeviceError:
            return "device-error";
        case SessionEventKind::kDeviceBack:
            return "device-back";
        case SessionEventKind::kDeviceWarning:
            return "device-warning";
    }
    return "unknown";
}

CaptureSession::Impl::Impl(std::unique_ptr<SessionStore> store_in, CaptureSessionConfig config_in,
                           SessionEventSink sink_in)
    : store(std::move(store_in)),
      config(std::move(config_in)),
      sink(std::move(sink_in)),
      to_save(config.save_queue_capacity),
      registrar(config.registration) {}

void CaptureSession::Impl::emit(SessionEvent event) {
    if (sink) sink(event);
}

void CaptureSession::Impl::begin_work() {
    std::lock_guard lock(work_mutex);
    ++work_in_flight;
}

void CaptureSession::Impl::end_work() {
    std::lock_guard lock(work_mutex);
    if (work_in_flight > 0) --work_in_flight;
    work_done.notify_all();
}

Expected<std::unique_ptr<CaptureSession>> CaptureSession::start(std::unique_ptr<SessionStore> store,
                                                                CaptureSessionConfig config,
                                                                SessionEventSink sink) {
    if (!store) return fail(ErrorCode::kInvalidArgument, "capture session: no session store");
    auto impl = std::make_unique<Impl>(std::move(store), std::move(config), std::move(sink));
    Impl& self = *impl;
    // The registrar's state is rebuilt by registering the session's scans again; a capture
    // that only saves (register later) needs none of it, however many scans there are.
    if (self.config.register_live) self.requeue_session_scans();
    self.save_thread = std::jthread([&self] { self.save_loop(); });
    self.registration_thread = std::jthread([&self] { self.registration_loop(); });
    return std::unique_ptr<CaptureSession>(new CaptureSession(std::move(impl)));
}

CaptureSession::CaptureSession(std::unique_ptr<Impl> impl) : impl_(std::move(impl)) {}

CaptureSession::~CaptureSession() {
    // Order matters: no new captures, then every captured scan saved, then the worker.
    impl_->requests.close();
    if (impl_->scanner_thread.joinable()) {
        impl_->scanner_thread.request_stop();
        impl_->scanner_thread.join();
    }
    impl_->to_save.close();
    if (impl_->save_thread.joinable()) impl_->save_thread.join();
    impl_->to_register.close();
    if (impl_->registration_thread.joinable()) impl_->registration_thread.join();
}

Expected<void> CaptureSession::attach_scanner(std::string uri, ScannerOpener open) {
    if (impl_->scanner_thread.joinable())
        return fail(ErrorCode::kInvalidArgument,
                    "capture session: a scanner is already attached (" + impl_->scanner_uri + ")");
    if (!open) return fail(ErrorCode::kInvalidArgument, uri + ": no way to open the scanner");
    impl_->scanner_uri = std::move(uri);
    impl_->open_scanner = std::move(open);
    Impl& self = *impl_;
    impl_->scanner_thread =
        std::jthread([&self](std::stop_token stop) { self.scanner_loop(stop); });
    return {};
}

std::future<Expected<std::int64_t>> CaptureSession::capture(CaptureRequest request) {
    auto pending = std::make_shared<PendingCapture>();
    pending->request = std::move(request);
    auto future = pending->acknowledged.get_future();
    if (!impl_->scanner_thread.joinable()) {
        pending->acknowledged.set_value(
            fail(ErrorCode::kInvalidArgument, "capture session: no scanner attached"));
        return future;
    }
    impl_->begin_work();
    if (!impl_->requests.push(pending)) {
        impl_->end_work();
        pending->acknowledged.set_value(
            fail(ErrorCode::kCancelled, "capture session: stopping, capture not started"));
    }
    return future;
}

void CaptureSession::wait_until_idle() {
    std::unique_lock lock(impl_->work_mutex);
    impl_->work_done.wait(lock, [&] { return impl_->work_in_flight == 0; });
}

Expected<void> CaptureSession::exclude(std::int64_t seq, bool excluded) {
    if (auto ok = impl_->store->set_excluded(seq, excluded); !ok) return ok;
    // The worker owns the registrar: the change reaches it as a queue item.
    impl_->begin_work();
    SavedScan item{.seq = seq};
    item.exclude_change = excluded ? 1 : -1;
    impl_->to_register.push(std::move(item));
    return {};
}

Expected<void> CaptureSession::reregister(std::int64_t seq) {
    auto record = impl_->store->scan(seq);
    if (!record) return std::unexpected(record.error());
    if (record->excluded) {
        return fail(ErrorCode::kInvalidArgument, "scan " + std::to_string(seq) +
                                                     " is excluded: include it before "
                                                     "registering it again");
    }
    (void)impl_->store->add_event("reregister", "",
                                  "scan " + std::to_string(seq) + ": registered again");
    impl_->begin_work();
    // Like a scan of a reopened session, it keeps the latency it was registered with live.
    SavedScan item{.seq = seq, .resumed = true, .reregister = true};
    item.previous_latency_s = record->latency_s;
    impl_->to_register.push(std::move(item));
    return {};
}

Expected<void> CaptureSession::add_note(std::optional<std::int64_t> seq, std::string_view text) {
    return impl_->store->add_note(seq, text);
}

SessionStore& CaptureSession::store() { return *impl_->store; }

}  // namespace anascan::acquisition
