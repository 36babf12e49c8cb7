#include "sim_capture_run.hpp"

#include <thread>

namespace anascan::sim::detail {

using std::chrono::steady_clock;

bool take_from_budget(SimDeviceFaults* faults) {
    // A budget of -1, "never", stays.
    int left = faults ? faults->unplug_after_captures.load() : -1;
    while (left >= 0 && !faults->unplug_after_captures.compare_exchange_weak(left, left - 1)) {
    }
    return left == 0;
}

SimCaptureRun::SimCaptureRun(const drivers::CaptureControl& control, std::string uri,
                             const std::shared_ptr<SimDeviceFaults>& faults)
    : control_(control),
      uri_(std::move(uri)),
      faults_(faults),
      deadline_(steady_clock::now() + control.timeout),
      unplug_midway_(take_from_budget(faults_.get())) {}

bool SimCaptureRun::keep_going(double fraction, std::string_view stage) {
    // A stalled device delivers nothing: wait (in slices, so a stop ends it) for the timeout.
    while (faults_ && faults_->stalled.load() && !control_.stop.stop_requested() &&
           steady_clock::now() < deadline_)
        std::this_thread::sleep_for(std::chrono::milliseconds(5));
    if (control_.stop.stop_requested()) {
        reason_ = ErrorCode::kCancelled;
        return false;
    }
    if (steady_clock::now() >= deadline_) {
        reason_ = ErrorCode::kTimeout;
        return false;
    }
    if (unplug_midway_ && fraction >= 0.5) {
        reason_ = ErrorCode::kDisconnected;
        unplugged_ = true;
        return false;
    }
    if (control_.on_progress) control_.on_progress({fraction, std::string(stage)});
    return true;
}

Error SimCaptureRun::stop_reason() const {
    const auto ms = std::chrono::duration_cast<std::chrono::milliseconds>(control_.timeout);
    switch (reason_) {
        case ErrorCode::kTimeout:
            return Error{ErrorCode::kTimeout,
                         uri_ + ": no scan within " + std::to_string(ms.count()) + " ms"};
        case ErrorCode::kDisconnected:
            return Error{ErrorCode::kDisconnected, uri_ + ": device went away during the capture"};
        default:
            return Error{ErrorCode::kCancelled, uri_ + ": capture cancelled"};
    }
}

}  // namespace anascan::sim::detail
