#pragma once
// Small V4L2 helpers: ioctl with EINTR retry, fourcc mapping, capability queries.

#include <linux/videodev2.h>

#include <optional>
#include <string>

#include "anascan/drivers/settings.hpp"

namespace anascan::drivers::v4l2 {

/// ioctl retried on EINTR; returns 0 or the errno.
int xioctl(int fd, unsigned long request, void* arg);

std::optional<PixelFormat> from_fourcc(std::uint32_t fourcc);
std::uint32_t to_fourcc(PixelFormat format);

/// Every (size, format, rate) the device offers among the formats we understand: discrete
/// frame sizes (or the current size when the driver lists none), one profile per discrete
/// frame interval (rate 0 when the driver lists none).
std::vector<StreamProfile> query_profiles(int fd);

/// Frames per second in effect (VIDIOC_G_PARM); 0 when the driver does not say.
double query_frame_rate(int fd);

/// Asks for `rate_hz` (VIDIOC_S_PARM); returns 0 or the errno.
int set_frame_rate(int fd, double rate_hz);

/// The control's range, or nothing when the device lacks it.
std::optional<NumericRange> query_control(int fd, std::uint32_t id);

}  // namespace anascan::drivers::v4l2
