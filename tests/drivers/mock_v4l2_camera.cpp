#include "mock_v4l2_camera.hpp"

#include <linux/videodev2.h>
#include <umockdev.h>

#include <algorithm>
#include <cerrno>
#include <cstddef>
#include <cstring>

namespace anascan::drivers::test {
namespace {

std::uint32_t fourcc(PixelFormat f) {
    switch (f) {
        case PixelFormat::kGrey8:
            return V4L2_PIX_FMT_GREY;
        case PixelFormat::kYuyv:
            return V4L2_PIX_FMT_YUYV;
        case PixelFormat::kMjpeg:
            return V4L2_PIX_FMT_MJPEG;
        case PixelFormat::kZ16:
            return V4L2_PIX_FMT_Z16;
    }
    return 0;
}

gboolean on_ioctl(UMockdevIoctlBase*, UMockdevIoctlClient* client, gpointer self) {
    return static_cast<MockV4l2Camera*>(self)->handle_ioctl(client);
}

gboolean on_read(UMockdevIoctlBase*, UMockdevIoctlClient* client, gpointer self) {
    return static_cast<MockV4l2Camera*>(self)->handle_read(client);
}

template <class T>
T* as(UMockdevIoctlData* d) {
    return reinterpret_cast<T*>(d->data);
}

}  // namespace

MockV4l2Camera::MockV4l2Camera(Testbed& testbed, MockV4l2Config config)
    : testbed_(testbed), config_(std::move(config)), format_(config_.formats.front()) {
    sysfs_path_ = testbed_.add_from_string("P: /devices/virtual/video4linux/" + config_.node +
                                           "\nN: " + config_.node +
                                           "\nE: SUBSYSTEM=video4linux\nE: DEVNAME=/dev/" +
                                           config_.node + "\nA: name=" + config_.card + "\n");
    handler_ = umockdev_ioctl_base_new();
    g_signal_connect(handler_, "handle-ioctl", G_CALLBACK(on_ioctl), this);
    g_signal_connect(handler_, "handle-read", G_CALLBACK(on_read), this);
    testbed_.attach(dev_path(), handler_);
}

MockV4l2Camera::~MockV4l2Camera() {
    testbed_.detach(dev_path());
    g_object_unref(handler_);
}

void MockV4l2Camera::unplug_now() {
    unplugged_ = true;
    testbed_.remove(sysfs_path_);
}

int MockV4l2Camera::queued_buffers() const {
    std::lock_guard lock(mutex_);
    return static_cast<int>(queued_indices_.size());
}

std::size_t MockV4l2Camera::image_bytes() const {
    const std::size_t px = static_cast<std::size_t>(config_.width) * config_.height;
    return format_ == PixelFormat::kMjpeg ? px
                                          : px * std::max<std::size_t>(1, bytes_per_pixel(format_));
}

std::vector<std::uint8_t> MockV4l2Camera::render_frame(std::uint64_t seq) const {
    if (config_.frame_source) return config_.frame_source();
    if (format_ == PixelFormat::kMjpeg) {  // SOI, a sequence byte, EOI: enough for the checks
        return {0xFF, 0xD8, static_cast<std::uint8_t>(seq), 0xFF, 0xD9};
    }
    std::vector<std::uint8_t> out;
    out.reserve(image_bytes());
    for (int r = 0; r < config_.height; ++r) {
        for (int c = 0; c < config_.width; ++c) {
            const std::uint16_t v = mock_pixel(r, c, seq);
            out.push_back(static_cast<std::uint8_t>(v & 0xFF));
            if (format_ != PixelFormat::kGrey8) out.push_back(static_cast<std::uint8_t>(v >> 8));
        }
    }
    return out;
}

std::vector<std::uint8_t> MockV4l2Camera::next_bytes() {
    const std::uint64_t seq = frames_sent_++;
    if (!frozen_) frozen_seq_.reset();
    if (frozen_ && !frozen_seq_) frozen_seq_ = seq;
    std::vector<std::uint8_t> bytes = render_frame(frozen_seq_.value_or(seq));
    const int every = garbled_every_.load();
    if (every > 0 && (seq + 1) % static_cast<std::uint64_t>(every) == 0)
        bytes.resize(bytes.size() / 2);
    return bytes;
}

MockV4l2Camera::Taken MockV4l2Camera::take_frame() {
    Taken now{next_bytes(), std::chrono::steady_clock::now().time_since_epoch()};
    if (!config_.one_frame_late) return now;
    if (!pending_) pending_ = Taken{render_frame(frames_sent_), now.at};
    Taken out = std::move(*pending_);
    pending_ = std::move(now);
    return out;
}

bool MockV4l2Camera::next_frame_available() {
    if (unplug_after_.load() == 0) unplugged_ = true;
    if (unplugged_ || stalled_) return false;
    if (unplug_after_.load() > 0) --unplug_after_;
    return true;
}

bool MockV4l2Camera::handle_read(void* c) {
    auto* client = static_cast<UMockdevIoctlClient*>(c);
    UMockdevIoctlData* arg = umockdev_ioctl_client_get_arg(client);
    std::lock_guard lock(mutex_);
    if (!next_frame_available()) {
        umockdev_ioctl_client_complete(client, -1, unplugged_ ? ENODEV : EAGAIN);
        return true;
    }
    const std::vector<std::uint8_t> frame = next_bytes();
    const std::size_t n =
        std::min<std::size_t>(frame.size(), static_cast<std::size_t>(arg->data_len));
    std::memcpy(arg->data, frame.data(), n);
    umockdev_ioctl_client_complete(client, static_cast<glong>(n), 0);
    return true;
}

int MockV4l2Camera::query_capability(v4l2_capability* cap) const {
    std::memset(cap, 0, sizeof(*cap));
    std::strncpy(reinterpret_cast<char*>(cap->driver), "anascan-mock", sizeof(cap->driver) - 1);
    std::strncpy(reinterpret_cast<char*>(cap->card), config_.card.c_str(), sizeof(cap->card) - 1);
    std::strncpy(reinterpret_cast<char*>(cap->bus_info), "platform:mock",
                 sizeof(cap->bus_info) - 1);
    cap->device_caps = V4L2_CAP_VIDEO_CAPTURE | (config_.can_read ? V4L2_CAP_READWRITE : 0) |
                       (config_.streaming ? V4L2_CAP_STREAMING : 0);
    cap->capabilities = cap->device_caps | V4L2_CAP_DEVICE_CAPS;
    return 0;
}

int MockV4l2Camera::set_or_get_format(bool set, v4l2_format* f) {
    if (set) {
        auto it = std::find_if(config_.formats.begin(), config_.formats.end(),
                               [&](PixelFormat x) { return fourcc(x) == f->fmt.pix.pixelformat; });
        if (it == config_.formats.end()) return EINVAL;
        format_ = *it;
    }
    f->fmt.pix.width = static_cast<std::uint32_t>(config_.width);  // the only size
    f->fmt.pix.height = static_cast<std::uint32_t>(config_.height);
    f->fmt.pix.pixelformat = fourcc(format_);
    f->fmt.pix.bytesperline =
        format_ == PixelFormat::kMjpeg
            ? 0
            : static_cast<std::uint32_t>(config_.width * bytes_per_pixel(format_));
    f->fmt.pix.sizeimage = static_cast<std::uint32_t>(image_bytes());
    return 0;
}

int MockV4l2Camera::exposure_control(bool set, v4l2_control* c) {
    if (c->id == V4L2_CID_EXPOSURE_AUTO && set) return 0;
    if (c->id != V4L2_CID_EXPOSURE_ABSOLUTE) return EINVAL;
    if (!set) {
        c->value = exposure_;
        return 0;
    }
    if (c->value < config_.exposure_min || c->value > config_.exposure_max) return ERANGE;
    exposure_ = c->value;
    return 0;
}

int MockV4l2Camera::enumerate(unsigned long request, void* p) const {
    if (request == VIDIOC_ENUM_FMT) {
        auto* d = static_cast<v4l2_fmtdesc*>(p);
        if (d->index >= config_.formats.size()) return EINVAL;
        d->pixelformat = fourcc(config_.formats[d->index]);
        return 0;
    }
    if (request == VIDIOC_ENUM_FRAMESIZES) {
        auto* s = static_cast<v4l2_frmsizeenum*>(p);
        if (s->index != 0) return EINVAL;
        s->type = V4L2_FRMSIZE_TYPE_DISCRETE;
        s->discrete = {static_cast<std::uint32_t>(config_.width),
                       static_cast<std::uint32_t>(config_.height)};
        return 0;
    }
    auto* i = static_cast<v4l2_frmivalenum*>(p);  // VIDIOC_ENUM_FRAMEINTERVALS: 30 and 15 Hz
    if (i->index > 1) return EINVAL;
    i->type = V4L2_FRMIVAL_TYPE_DISCRETE;
    i->discrete = {1, i->index == 0 ? 30u : 15u};
    return 0;
}

int MockV4l2Camera::handle_format_ioctl(unsigned long request, void* p) {
    switch (request) {
        case VIDIOC_QUERYCAP:
            return query_capability(static_cast<v4l2_capability*>(p));
        case VIDIOC_ENUM_FMT:
        case VIDIOC_ENUM_FRAMESIZES:
        case VIDIOC_ENUM_FRAMEINTERVALS:
            return enumerate(request, p);
        case VIDIOC_S_FMT:
        case VIDIOC_G_FMT:
            return set_or_get_format(request == VIDIOC_S_FMT, static_cast<v4l2_format*>(p));
        case VIDIOC_G_PARM:
        case VIDIOC_S_PARM: {
            v4l2_fract& t = static_cast<v4l2_streamparm*>(p)->parm.capture.timeperframe;
            if (request == VIDIOC_S_PARM && t.numerator != 0)
                rate_hz_ = static_cast<int>(t.denominator / t.numerator);
            t = {1, static_cast<std::uint32_t>(rate_hz_)};
            return 0;
        }
        case VIDIOC_QUERYCTRL: {
            auto* q = static_cast<v4l2_queryctrl*>(p);
            if (q->id != V4L2_CID_EXPOSURE_ABSOLUTE) return EINVAL;
            q->minimum = config_.exposure_min;
            q->maximum = config_.exposure_max;
            q->flags = 0;
            return 0;
        }
        case VIDIOC_G_CTRL:
        case VIDIOC_S_CTRL:
            return exposure_control(request == VIDIOC_S_CTRL, static_cast<v4l2_control*>(p));
        default:
            return ENOTTY;
    }
}

int MockV4l2Camera::dequeue_buffer(void* c, void* d) {
    auto* data = static_cast<UMockdevIoctlData*>(d);
    if (queued_indices_.empty() || !next_frame_available()) return unplugged_ ? ENODEV : EAGAIN;
    const Taken taken = take_frame();
    const std::vector<std::uint8_t>& frame = taken.bytes;
    auto* b = as<v4l2_buffer>(data);
    b->flags = V4L2_BUF_FLAG_TIMESTAMP_MONOTONIC | V4L2_BUF_FLAG_TSTAMP_SRC_SOE;
    b->timestamp.tv_sec = static_cast<time_t>(taken.at.count() / 1000000000);
    b->timestamp.tv_usec = static_cast<suseconds_t>(taken.at.count() % 1000000000 / 1000);
    b->index = queued_indices_.front();
    b->m.userptr = queued_userptrs_.front();
    b->bytesused = static_cast<std::uint32_t>(frame.size());
    b->memory = V4L2_MEMORY_USERPTR;
    queued_indices_.erase(queued_indices_.begin());
    queued_userptrs_.erase(queued_userptrs_.begin());
    GError* error = nullptr;
    UMockdevIoctlData* target =
        umockdev_ioctl_data_resolve(data, offsetof(v4l2_buffer, m.userptr), frame.size(), &error);
    if (target == nullptr) {
        g_error_free(error);
        return EFAULT;
    }
    std::memcpy(target->data, frame.data(), frame.size());
    umockdev_ioctl_client_complete(static_cast<UMockdevIoctlClient*>(c), 0, 0);
    g_object_unref(target);
    return -1;  // already completed
}

int MockV4l2Camera::handle_buffer_ioctl(void* c, unsigned long request, void* d) {
    auto* data = static_cast<UMockdevIoctlData*>(d);
    switch (request) {
        case VIDIOC_REQBUFS: {
            auto* r = as<v4l2_requestbuffers>(data);
            if (r->memory != V4L2_MEMORY_USERPTR || !config_.streaming) return EINVAL;
            queued_indices_.clear();
            queued_userptrs_.clear();
            return 0;
        }
        case VIDIOC_QBUF: {
            auto* b = as<v4l2_buffer>(data);
            queued_indices_.push_back(b->index);
            queued_userptrs_.push_back(b->m.userptr);
            return 0;
        }
        case VIDIOC_DQBUF:
            return dequeue_buffer(c, data);
        case VIDIOC_STREAMON:
            ++streamon_count_;
            return 0;
        case VIDIOC_STREAMOFF:
            return 0;
        default:
            return ENOTTY;
    }
}

bool MockV4l2Camera::handle_ioctl(void* c) {
    auto* client = static_cast<UMockdevIoctlClient*>(c);
    const unsigned long request = umockdev_ioctl_client_get_request(client);
    std::lock_guard lock(mutex_);
    if (unplugged_) {
        umockdev_ioctl_client_complete(client, -1, ENODEV);
        return true;
    }
    GError* error = nullptr;
    UMockdevIoctlData* data = umockdev_ioctl_data_resolve(umockdev_ioctl_client_get_arg(client), 0,
                                                          _IOC_SIZE(request), &error);
    if (data == nullptr) {
        g_error_free(error);
        umockdev_ioctl_client_complete(client, -1, EFAULT);
        return true;
    }
    const bool blocked = busy_ && (request == VIDIOC_S_FMT || request == VIDIOC_REQBUFS);
    int result = blocked ? EBUSY : handle_format_ioctl(request, data->data);
    if (result == ENOTTY) result = handle_buffer_ioctl(client, request, data);
    if (result >= 0) umockdev_ioctl_client_complete(client, result == 0 ? 0 : -1, result);
    g_object_unref(data);
    return true;
}

}  // namespace anascan::drivers::test
