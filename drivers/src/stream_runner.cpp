#include "anascan/drivers/stream_runner.hpp"

namespace anascan::drivers {

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

void StreamRunner::run(std::stop_token stop) {
    int timeouts = 0;
    while (!stop.stop_requested()) {
        Expected<Frame> frame = camera_.next_frame(config_.frame_timeout);
        if (frame) {
            timeouts = 0;
            ++frames_;
            if (callbacks_.on_frame) callbacks_.on_frame(*frame);
            continue;
        }
        const bool retry = frame.error().code == ErrorCode::kTimeout &&
                           ++timeouts < config_.max_consecutive_timeouts;
        if (retry) continue;
        if (!stop.stop_requested() && callbacks_.on_error) callbacks_.on_error(frame.error());
        break;
    }
    running_ = false;
}

}  // namespace anascan::drivers
