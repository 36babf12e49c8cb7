// V4L2 streaming: read() or user-pointer buffers, dequeue with a timeout.
#include <poll.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>

#include "os_error.hpp"
#include "v4l2_camera_impl.hpp"
#include "v4l2_query.hpp"

namespace anascan::drivers {

Expected<void> V4l2Camera::start_stream() {
    if (auto ok = check_open(); !ok) return ok;
    if (streaming_) return fail(ErrorCode::kBusy, config_.device_path + ": already streaming");
    use_read_ =
        config_.io == V4l2IoMethod::kRead || (config_.io == V4l2IoMethod::kAuto && can_read_);
    if (use_read_ && !can_read_) {
        return fail(ErrorCode::kUnsupported, config_.device_path + ": the driver has no read()");
    }
    if (!use_read_) {
        if (!can_stream_io_) {
            return fail(ErrorCode::kUnsupported,
                        config_.device_path + ": the driver offers neither read() nor streaming");
        }
        if (auto ok = start_user_pointers(); !ok) return ok;
    }
    sequence_ = 0;
    streaming_ = true;
    return {};
}

Expected<void> V4l2Camera::start_user_pointers() {
    v4l2_requestbuffers req{};
    req.count = static_cast<std::uint32_t>(config_.buffer_count);
    req.type = V4L2_BUF_TYPE_VIDEO_CAPTURE;
    req.memory = V4L2_MEMORY_USERPTR;
    if (int e = v4l2::xioctl(fd_.get(), VIDIOC_REQBUFS, &req))
        return fail(fail_os("VIDIOC_REQBUFS", e));
    buffers_.assign(req.count, std::vector<std::uint8_t>(image_bytes_));
    for (std::uint32_t i = 0; i < req.count; ++i) {
        v4l2_buffer b{};
        b.type = V4L2_BUF_TYPE_VIDEO_CAPTURE;
        b.memory = V4L2_MEMORY_USERPTR;
        b.index = i;
        b.m.userptr = reinterpret_cast<unsigned long>(buffers_[i].data());
        b.length = static_cast<std::uint32_t>(buffers_[i].size());
        if (int e = v4l2::xioctl(fd_.get(), VIDIOC_QBUF, &b))
            return fail(fail_os("VIDIOC_QBUF", e));
    }
    int type = V4L2_BUF_TYPE_VIDEO_CAPTURE;
    if (int e = v4l2::xioctl(fd_.get(), VIDIOC_STREAMON, &type))
        return fail(fail_os("VIDIOC_STREAMON", e));
    return {};
}

void V4l2Camera::stop_stream() {
    if (!streaming_) return;
    streaming_ = false;
    if (!use_read_ && fd_ && !disconnected_) {
        int type = V4L2_BUF_TYPE_VIDEO_CAPTURE;
        (void)v4l2::xioctl(fd_.get(), VIDIOC_STREAMOFF, &type);
        v4l2_requestbuffers req{};
        req.type = V4L2_BUF_TYPE_VIDEO_CAPTURE;
        req.memory = V4L2_MEMORY_USERPTR;
        (void)v4l2::xioctl(fd_.get(), VIDIOC_REQBUFS, &req);  // count 0 frees the queue
    }
    buffers_.clear();
}

Frame V4l2Camera::make_frame(const std::uint8_t* data, std::size_t bytes,
                             std::chrono::nanoseconds exposure_start) {
    Frame f;
    f.width = settings_.profile ? settings_.profile->width : 0;
    f.height = settings_.profile ? settings_.profile->height : 0;
    f.format = settings_.profile ? settings_.profile->format : PixelFormat::kGrey8;
    f.stride_bytes = f.format == PixelFormat::kMjpeg ? 0 : stride_bytes_;
    f.sequence = sequence_++;
    f.timestamp_ns = exposure_start.count() != 0
                         ? exposure_start
                         : std::chrono::steady_clock::now().time_since_epoch();
    f.data.assign(data, data + bytes);
    return f;
}

Expected<Frame> V4l2Camera::try_read() {
    std::vector<std::uint8_t> buffer(image_bytes_);
    const ssize_t n = ::read(fd_.get(), buffer.data(), buffer.size());
    if (n < 0) {
        const int e = errno;
        if (e == EAGAIN || e == EINTR) return fail(ErrorCode::kTimeout, "");
        return fail(fail_os("read", e));
    }
    Frame f = make_frame(buffer.data(), static_cast<std::size_t>(n));
    if (auto ok = check_frame(f, info_.uri); !ok) return fail(ok.error());
    return f;
}

// The start of the frame's exposure from a buffer's CLOCK_MONOTONIC time stamp (the clock of
// std::chrono::steady_clock): start of exposure as is, end of frame minus one frame
// interval; zero when the driver gives no monotonic stamp.
std::chrono::nanoseconds V4l2Camera::exposure_start(const v4l2_buffer& b) const {
    using namespace std::chrono;
    if ((b.flags & V4L2_BUF_FLAG_TIMESTAMP_MASK) != V4L2_BUF_FLAG_TIMESTAMP_MONOTONIC ||
        (b.timestamp.tv_sec == 0 && b.timestamp.tv_usec == 0))
        return nanoseconds(0);
    nanoseconds t = seconds(b.timestamp.tv_sec) + microseconds(b.timestamp.tv_usec);
    const double rate_hz = settings_.profile ? settings_.profile->frame_rate_hz : 0.0;
    if ((b.flags & V4L2_BUF_FLAG_TSTAMP_SRC_MASK) == V4L2_BUF_FLAG_TSTAMP_SRC_EOF && rate_hz > 0.0)
        t -= duration_cast<nanoseconds>(duration<double>(1.0 / rate_hz));
    return t;
}

Expected<Frame> V4l2Camera::try_user_pointer() {
    v4l2_buffer b{};
    b.type = V4L2_BUF_TYPE_VIDEO_CAPTURE;
    b.memory = V4L2_MEMORY_USERPTR;
    if (int e = v4l2::xioctl(fd_.get(), VIDIOC_DQBUF, &b)) {
        if (e == EAGAIN) return fail(ErrorCode::kTimeout, "");
        return fail(fail_os("VIDIOC_DQBUF", e));
    }
    if (b.index >= buffers_.size() || b.bytesused > buffers_[b.index].size()) {
        return fail(ErrorCode::kIo, config_.device_path + ": the driver returned buffer " +
                                        std::to_string(b.index) + " with " +
                                        std::to_string(b.bytesused) + " bytes");
    }
    Frame f = make_frame(buffers_[b.index].data(), b.bytesused, exposure_start(b));
    b.m.userptr = reinterpret_cast<unsigned long>(buffers_[b.index].data());
    b.length = static_cast<std::uint32_t>(buffers_[b.index].size());
    if (int e = v4l2::xioctl(fd_.get(), VIDIOC_QBUF, &b)) return fail(fail_os("VIDIOC_QBUF", e));
    if (auto ok = check_frame(f, info_.uri); !ok) return fail(ok.error());
    return f;
}

Expected<Frame> V4l2Camera::try_dequeue() { return use_read_ ? try_read() : try_user_pointer(); }

// Try first, then wait: a real driver makes poll() wait for the next frame; a mocked node
// (umockdev) never signals poll(), so the frames it has ready are taken by the first try.
Expected<Frame> V4l2Camera::next_frame(std::chrono::milliseconds timeout) {
    if (auto ok = check_open(); !ok) return fail(ok.error());
    if (!streaming_)
        return fail(ErrorCode::kInvalidArgument, config_.device_path + ": not streaming");
    Expected<Frame> frame = try_dequeue();
    if (frame || frame.error().code != ErrorCode::kTimeout) return frame;
    pollfd p{fd_.get(), POLLIN, 0};
    int r;
    do {
        r = ::poll(&p, 1, static_cast<int>(timeout.count()));
    } while (r < 0 && errno == EINTR);
    if (r < 0) return fail(fail_os("poll", errno));
    frame = try_dequeue();
    if (frame || frame.error().code != ErrorCode::kTimeout) return frame;
    return fail(ErrorCode::kTimeout, config_.device_path + ": no frame within " +
                                         std::to_string(timeout.count()) + " ms");
}

}  // namespace anascan::drivers
