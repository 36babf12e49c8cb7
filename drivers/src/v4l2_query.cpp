#include "v4l2_query.hpp"

#include <sys/ioctl.h>

#include <cerrno>
#include <cmath>

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

/// One profile per discrete frame interval of the size (rate 0 when the driver lists none).
void add_rates(int fd, std::uint32_t fourcc, StreamProfile p, std::vector<StreamProfile>& out) {
    v4l2_frmivalenum ival{};
    ival.pixel_format = fourcc;
    ival.width = static_cast<std::uint32_t>(p.width);
    ival.height = static_cast<std::uint32_t>(p.height);
    const std::size_t before = out.size();
    for (ival.index = 0; xioctl(fd, VIDIOC_ENUM_FRAMEINTERVALS, &ival) == 0; ++ival.index) {
        if (ival.type != V4L2_FRMIVAL_TYPE_DISCRETE || ival.discrete.numerator == 0) break;
        p.frame_rate_hz = static_cast<double>(ival.discrete.denominator) / ival.discrete.numerator;
        out.push_back(p);
    }
    if (out.size() == before) out.push_back(p);
}

void add_sizes(int fd, std::uint32_t fourcc, PixelFormat format, std::vector<StreamProfile>& out) {
    v4l2_frmsizeenum size{};
    size.pixel_format = fourcc;
    const std::size_t before = out.size();
    for (size.index = 0; xioctl(fd, VIDIOC_ENUM_FRAMESIZES, &size) == 0; ++size.index) {
        if (size.type != V4L2_FRMSIZE_TYPE_DISCRETE) break;
        add_rates(fd, fourcc,
                  {static_cast<int>(size.discrete.width), static_cast<int>(size.discrete.height),
                   format, 0.0},
                  out);
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

double query_frame_rate(int fd) {
    v4l2_streamparm parm{};
    parm.type = V4L2_BUF_TYPE_VIDEO_CAPTURE;
    if (xioctl(fd, VIDIOC_G_PARM, &parm) != 0 || parm.parm.capture.timeperframe.numerator == 0)
        return 0.0;
    return static_cast<double>(parm.parm.capture.timeperframe.denominator) /
           parm.parm.capture.timeperframe.numerator;
}

int set_frame_rate(int fd, double rate_hz) {
    v4l2_streamparm parm{};
    parm.type = V4L2_BUF_TYPE_VIDEO_CAPTURE;
    parm.parm.capture.timeperframe.numerator = 1000;
    parm.parm.capture.timeperframe.denominator =
        static_cast<std::uint32_t>(std::lround(rate_hz * 1000.0));
    return xioctl(fd, VIDIOC_S_PARM, &parm);
}

}  // namespace anascan::drivers::v4l2
