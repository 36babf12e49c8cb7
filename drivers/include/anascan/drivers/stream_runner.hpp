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
    /// kTimeout after `max_consecutive_timeouts`, kFormat after `max_consecutive_bad_frames`);
    /// not called after stop().
    std::function<void(const Error&)> on_error;
    /// Called on the capture thread for what the stream survives: an unreadable frame
    /// (dropped, kFormat, naming the device), or `identical_frames_warning` identical frames
    /// in a row (a frozen camera, or one that sees nothing), once per such run.
    std::function<void(const Error&)> on_warning;
};

struct StreamRunnerConfig {
    std::chrono::milliseconds frame_timeout{1000};  ///< Wait per frame.
    int max_consecutive_timeouts = 3;               ///< Then the stream ends with kTimeout.
    /// Unreadable frames (short, bad header, not an image) are dropped; this many in a row
    /// end the stream with kFormat: the camera delivers nothing usable.
    int max_consecutive_bad_frames = 30;
    /// A real sensor's noise never repeats a frame bit for bit; this many identical frames
    /// in a row are reported (on_warning). 0: never.
    int identical_frames_warning = 30;
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
    /// Unreadable frames dropped so far.
    std::uint64_t frames_dropped() const { return dropped_.load(); }

private:
    StreamRunner(Camera& camera, StreamCallbacks callbacks, const StreamRunnerConfig& config);
    void run(std::stop_token stop);
    /// A readable frame: delivered, and counted when it repeats the previous one.
    void deliver(const Frame& frame);
    /// An unreadable one: dropped and reported; false once too many came in a row.
    bool drop(const Error& error);

    Camera& camera_;
    StreamCallbacks callbacks_;
    StreamRunnerConfig config_;
    std::atomic<bool> running_{true};
    std::atomic<std::uint64_t> frames_{0};
    std::atomic<std::uint64_t> dropped_{0};
    int bad_in_a_row_ = 0;        // Capture thread only.
    int identical_in_a_row_ = 0;  // Capture thread only.
    std::uint64_t last_digest_ = 0;
    std::jthread thread_;
};

}  // namespace anascan::drivers
