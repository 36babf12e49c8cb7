#include "anascan/drivers/frame.hpp"

#include <string>

namespace anascan::drivers {

std::string_view to_string(PixelFormat format) {
    switch (format) {
        case PixelFormat::kGrey8:
            return "grey8";
        case PixelFormat::kYuyv:
            return "yuyv";
        case PixelFormat::kMjpeg:
            return "mjpeg";
        case PixelFormat::kZ16:
            return "z16";
    }
    return "unknown";
}

Expected<PixelFormat> parse_pixel_format(std::string_view name) {
    for (PixelFormat f :
         {PixelFormat::kGrey8, PixelFormat::kYuyv, PixelFormat::kMjpeg, PixelFormat::kZ16}) {
        if (to_string(f) == name) return f;
    }
    return fail(ErrorCode::kInvalidArgument, "unknown pixel format '" + std::string(name) +
                                                 "' (expected grey8, yuyv, mjpeg or z16)");
}

std::size_t bytes_per_pixel(PixelFormat format) {
    switch (format) {
        case PixelFormat::kGrey8:
            return 1;
        case PixelFormat::kYuyv:
        case PixelFormat::kZ16:
            return 2;
        case PixelFormat::kMjpeg:
            return 0;
    }
    return 0;
}

Expected<void> check_frame(const Frame& frame, std::string_view source) {
    const std::string where(source);
    if (frame.width <= 0 || frame.height <= 0) {
        return fail(ErrorCode::kFormat, where + ": frame " + std::to_string(frame.sequence) +
                                            " has no pixels (" + std::to_string(frame.width) +
                                            " x " + std::to_string(frame.height) + ")");
    }
    if (frame.format == PixelFormat::kMjpeg) {
        if (frame.data.size() < 4 || frame.data[0] != 0xFF || frame.data[1] != 0xD8) {
            return fail(ErrorCode::kFormat, where + ": frame " + std::to_string(frame.sequence) +
                                                " is not a JPEG image (no SOI marker)");
        }
        return {};
    }
    const std::size_t row = bytes_per_pixel(frame.format) * static_cast<std::size_t>(frame.width);
    const std::size_t need = frame.stride_bytes * static_cast<std::size_t>(frame.height);
    if (frame.stride_bytes < row || frame.data.size() < need) {
        return fail(ErrorCode::kFormat, where + ": frame " + std::to_string(frame.sequence) +
                                            " holds " + std::to_string(frame.data.size()) +
                                            " bytes, stride " + std::to_string(frame.stride_bytes) +
                                            "; " + std::string(to_string(frame.format)) + " " +
                                            std::to_string(frame.width) + " x " +
                                            std::to_string(frame.height) + " needs " +
                                            std::to_string(row * frame.height) + " bytes");
    }
    return {};
}

}  // namespace anascan::drivers
