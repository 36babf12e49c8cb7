#include "v4l2_query.hpp"

#include <sys/ioctl.h>

#include <cerrno>

namespace anascan::drivers::v4l2 {

int xioctl(int fd, unsigned long request, void* arg) {
    int r;
    do {
        r = ::ioctl(fd, request, arg);
    } while (r < 0 && errno == EINTR);
    return r < 0 ? errno : 0;
}

std::optional<PixelFormat> from_fourcc(std::uint32_t fourcc) {
    switch (fourcc) {
        case V4L2_PIX_FMT_GREY:
            return PixelFormat::kGrey8;
        case V4L2_PIX_FMT_YUYV:
            return PixelFormat::kYuyv;
        case V4L2_PIX_FMT_MJPEG:
            return PixelFormat::kMjpeg;
        case V4L2_PIX_FMT_Z16:
            return PixelFormat::kZ16;
        default:
            return std::nullopt;
    }
}

std::uint32_t to_fourcc(PixelFormat format) {
    switch (format) {
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

namespace {

void add_sizes(int fd, std::uint32_t fourcc, PixelFormat format, std::vector<StreamProfile>& out) {
    v4l2_frmsizeenum size{};
    size.pixel_format = fourcc;
    const std::size_t before = out.size();
    for (size.index = 0; xioctl(fd, VIDIOC_ENUM_FRAMESIZES, &size) == 0; ++size.index) {
        if (size.type != V4L2_FRMSIZE_TYPE_DISCRETE) break;
        out.push_back({static_cast<int>(size.discrete.width),
                       static_cast<int>(size.discrete.height), format, 0.0});
    }
    if (out.size() != before) return;
    v4l2_format current{};
    current.type = V4L2_BUF_TYPE_VIDEO_CAPTURE;
    if (xioctl(fd, VIDIOC_G_FMT, &current) == 0) {
        out.push_back({static_cast<int>(current.fmt.pix.width),
                       static_cast<int>(current.fmt.pix.height), format, 0.0});
    }
}

}  // namespace

std::vector<StreamProfile> query_profiles(int fd) {
    std::vector<StreamProfile> profiles;
    v4l2_fmtdesc desc{};
    desc.type = V4L2_BUF_TYPE_VIDEO_CAPTURE;
    for (desc.index = 0; xioctl(fd, VIDIOC_ENUM_FMT, &desc) == 0; ++desc.index) {
        if (auto format = from_fourcc(desc.pixelformat))
            add_sizes(fd, desc.pixelformat, *format, profiles);
    }
    return profiles;
}

std::optional<NumericRange> query_control(int fd, std::uint32_t id) {
    v4l2_queryctrl q{};
    q.id = id;
    if (xioctl(fd, VIDIOC_QUERYCTRL, &q) != 0 || (q.flags & V4L2_CTRL_FLAG_DISABLED)) {
        return std::nullopt;
    }
    return NumericRange{static_cast<double>(q.minimum), static_cast<double>(q.maximum)};
}

}  // namespace anascan::drivers::v4l2
