#pragma once
// A camera frame as an 8-bit grey image (what the structured-light decoder reads).

#include <opencv2/core/mat.hpp>
#include <string_view>

#include "anascan/drivers/frame.hpp"

namespace anascan::drivers {

/// grey8: copied; YUYV: its luma; MJPEG: decoded as grey. kFormat for Z16 or an image
/// that cannot be read, naming `source`.
Expected<cv::Mat> frame_to_grey(const Frame& frame, std::string_view source);

}  // namespace anascan::drivers
