#pragma once
// The V4L2 camera class, shared by v4l2_camera.cpp (open, query, configure) and
// v4l2_stream.cpp (buffers, streaming, dequeue with timeout).

#include <linux/videodev2.h>

#include <chrono>
#include <cstdint>
#include <vector>

#include "anascan/drivers/v4l2_camera.hpp"
#include "unique_fd.hpp"

namespace anascan::drivers {

/// Not thread-safe (see Camera). Owns the device node's descriptor.
class V4l2Camera final : public Camera {
public:
    V4l2Camera(V4l2CameraConfig config, UniqueFd fd, DeviceInfo info, bool can_read,
               bool can_stream_io);
    ~V4l2Camera() override { close(); }

    const DeviceInfo& info() const override { return info_; }
    const Capabilities& capabilities() const override { return caps_; }
    DeviceSettings settings() const override { return settings_; }
    Expected<void> configure(const DeviceSettings& requested) override;
    void close() override;

    Expected<void> start_stream() override;
    Expected<Frame> next_frame(std::chrono::milliseconds timeout) override;
    void stop_stream() override;

    /// Reads the current format and controls into settings_ (after open and configure).
    Expected<void> refresh_settings();
    /// A camera offering Z16 depth is a time-of-flight sensor.
    void mark_depth_camera() {
        for (const StreamProfile& p : caps_.profiles)
            if (p.format == PixelFormat::kZ16) info_.kind = DeviceKind::kTimeOfFlight;
    }

private:
    Expected<void> apply_profile(const StreamProfile& profile);
    Expected<void> apply_control(std::uint32_t id, std::int32_t value, const char* name);
    Expected<void> check_open() const;
    Error fail_os(const std::string& what, int error_number);
    Expected<void> start_user_pointers();
    /// One non-blocking attempt: a frame, kTimeout (nothing yet) or another error.
    Expected<Frame> try_dequeue();
    Expected<Frame> try_read();
    Expected<Frame> try_user_pointer();
    std::chrono::nanoseconds exposure_start(const v4l2_buffer& b) const;
    /// `exposure_start`: from the driver's time stamp; zero: the host's time now.
    Frame make_frame(const std::uint8_t* data, std::size_t bytes,
                     std::chrono::nanoseconds exposure_start = {});

    V4l2CameraConfig config_;
    UniqueFd fd_;
    DeviceInfo info_;
    Capabilities caps_;
    DeviceSettings settings_;
    bool can_read_ = false;
    bool can_stream_io_ = false;
    bool use_read_ = false;
    bool streaming_ = false;
    bool disconnected_ = false;
    std::size_t image_bytes_ = 0;  ///< sizeimage of the current format.
    std::size_t stride_bytes_ = 0;
    std::uint64_t sequence_ = 0;
    std::vector<std::vector<std::uint8_t>> buffers_;  ///< User-pointer buffers.
};

}  // namespace anascan::drivers
