#include "anascan/drivers/stream_runner.hpp"

#include <string>

namespace anascan::drivers {
namespace {

/// FNV-1a 64 over a frame's bytes.
std::uint64_t digest(const std::vector<std::uint8_t>& bytes) {
    std::uint64_t h = 1469598103934665603ull;
    for (const std::uint8_t b : bytes) h = (h ^ b) * 1099511628211ull;
    return h;
}

}  // namespace

Expected<std::unique_ptr<StreamRunner>> StreamRunner::start(Camera& camera,
                                                            StreamCallbacks callbacks,
                                                            const StreamRunnerConfig& config) {
    if (auto ok = camera.start_stream(); !ok) return fail(ok.error());
    return std::unique_ptr<StreamRunner>(new StreamRunner(camera, std::move(callbacks), config));
}

StreamRunner::StreamRunner(Camera& camera, StreamCallbacks callbacks,
                           const StreamRunnerConfig& config)
    : camera_(camera), callbacks_(std::move(callbacks)), config_(config) {
    thread_ = std::jthread([this](std::stop_token stop) { run(stop); });
}

StreamRunner::~StreamRunner() { stop(); }

void StreamRunner::stop() {
    if (thread_.joinable()) {
        thread_.request_stop();
        thread_.join();
        camera_.stop_stream();
    }
    running_ = false;
}

void StreamRunner::deliver(const Frame& frame) {
    bad_in_a_row_ = 0;
    ++frames_;
    const std::uint64_t d = digest(frame.data);
    identical_in_a_row_ = frames_ > 1 && d == last_digest_ ? identical_in_a_row_ + 1 : 1;
    last_digest_ = d;
    if (identical_in_a_row_ == config_.identical_frames_warning && callbacks_.on_warning) {
        callbacks_.on_warning(
            Error{ErrorCode::kFormat, camera_.info().uri + ": the last " +
                                          std::to_string(identical_in_a_row_) +
                                          " frames were identical bit for bit: the camera may be "
                                          "frozen (unplug and reconnect it), or it sees nothing "
                                          "(a covered lens)"});
    }
    if (callbacks_.on_frame) callbacks_.on_frame(frame);
}

bool StreamRunner::drop(const Error& error) {
    ++dropped_;
    if (++bad_in_a_row_ >= config_.max_consecutive_bad_frames) return false;
    if (callbacks_.on_warning)
        callbacks_.on_warning(Error{error.code, error.message + " (frame dropped)"});
    return true;
}

void StreamRunner::run(std::stop_token stop) {
    int timeouts = 0;
    while (!stop.stop_requested()) {
        Expected<Frame> frame = camera_.next_frame(config_.frame_timeout);
        if (frame) {
            timeouts = 0;
            deliver(*frame);
            continue;
        }
        const ErrorCode code = frame.error().code;
        if (code == ErrorCode::kFormat && drop(frame.error())) continue;
        const bool retry =
            code == ErrorCode::kTimeout && ++timeouts < config_.max_consecutive_timeouts;
        if (retry) continue;
        if (!stop.stop_requested() && callbacks_.on_error) {
            Error end = frame.error();
            if (code == ErrorCode::kFormat) {
                end.message += " (" + std::to_string(bad_in_a_row_) +
                               " unreadable frames in a row: the camera delivers nothing usable)";
            }
            callbacks_.on_error(end);
        }
        break;
    }
    running_ = false;
}

}  // namespace anascan::drivers
