#pragma once
/// \file
/// A streaming camera: start_stream → next_frame (with timeout) … → stop_stream. The pull
/// interface is what backends implement; StreamRunner (stream_runner.hpp) turns it into
/// callbacks on one capture thread.

#include <chrono>

#include "anascan/drivers/device.hpp"
#include "anascan/drivers/frame.hpp"

namespace anascan::drivers {

/// Not thread-safe: start_stream, next_frame and stop_stream are called from one thread
/// at a time (the capture thread while streaming).
class Camera : public Device {
public:
    Camera* as_camera() override { return this; }

    /// Allocates buffers and starts the device streaming with the current profile.
    virtual Expected<void> start_stream() = 0;
    /// The next frame, waiting at most `timeout`: kTimeout when none came, kDisconnected
    /// when the device went away (then the stream is over).
    virtual Expected<Frame> next_frame(std::chrono::milliseconds timeout) = 0;
    /// Stops streaming and frees the buffers; idempotent.
    virtual void stop_stream() = 0;
};

}  // namespace anascan::drivers
