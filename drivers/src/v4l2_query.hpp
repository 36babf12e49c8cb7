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

/// Every (size, format) the device offers among the formats we understand; discrete
/// frame sizes, or the current size when the driver lists none.
std::vector<StreamProfile> query_profiles(int fd);

/// The control's range, or nothing when the device lacks it.
std::optional<NumericRange> query_control(int fd, std::uint32_t id);

}  // namespace anascan::drivers::v4l2
