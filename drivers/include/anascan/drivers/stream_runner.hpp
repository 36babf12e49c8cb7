#pragma once
/// \file
/// The capture thread of a streaming camera: calls Camera::next_frame in a loop and hands
/// each frame to a callback (librealsense's start(callback) → stop()).

#include <atomic>
#include <chrono>
#include <cstdint>
#include <functional>
#include <memory>
#include <thread>

#include "anascan/drivers/camera.hpp"

namespace anascan::drivers {

struct StreamCallbacks {
    std::function<void(const Frame&)> on_frame;  ///< Called on the capture thread.
    /// Called once on the capture thread when the stream ends by an error (kDisconnected,
    /// or kTimeout after `max_consecutive_timeouts`); not called after stop().
    std::function<void(const Error&)> on_error;
};

struct StreamRunnerConfig {
    std::chrono::milliseconds frame_timeout{1000};  ///< Wait per frame.
    int max_consecutive_timeouts = 3;               ///< Then the stream ends with kTimeout.
};

/// Owns the single capture thread of one camera. Thread-safe: stop() and the counters may
/// be called from any thread. The camera must outlive the runner; destroying the runner
/// stops the thread and the camera's stream.
class StreamRunner {
public:
    /// Starts the camera's stream and the thread; errors of start_stream are returned.
    static Expected<std::unique_ptr<StreamRunner>> start(Camera& camera, StreamCallbacks callbacks,
                                                         const StreamRunnerConfig& config = {});
    ~StreamRunner();
    StreamRunner(const StreamRunner&) = delete;
    StreamRunner& operator=(const StreamRunner&) = delete;

    /// Asks the thread to stop, joins it (at most one frame timeout) and stops the stream.
    void stop();
    /// True until the thread ended (stop() or a stream error).
    bool running() const { return running_.load(); }
    std::uint64_t frames_delivered() const { return frames_.load(); }

private:
    StreamRunner(Camera& camera, StreamCallbacks callbacks, const StreamRunnerConfig& config);
    void run(std::stop_token stop);

    Camera& camera_;
    StreamCallbacks callbacks_;
    StreamRunnerConfig config_;
    std::atomic<bool> running_{true};
    std::atomic<std::uint64_t> frames_{0};
    std::jthread thread_;
};

}  // namespace anascan::drivers
