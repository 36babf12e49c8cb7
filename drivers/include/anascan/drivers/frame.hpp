#pragma once
/// \file
/// An image as a camera delivers it: grey, YUYV, MJPEG or 16-bit depth (Z16).

#include <chrono>
#include <cstddef>
#include <cstdint>
#include <string_view>
#include <vector>

#include "anascan/processing/core/expected.hpp"

namespace anascan::drivers {

/// Pixel layouts the device layer understands (V4L2 GREY, YUYV, MJPG, Z16).
enum class PixelFormat {
    kGrey8,  ///< 8-bit luminance, one byte per pixel.
    kYuyv,   ///< YUV 4:2:2 packed, two bytes per pixel.
    kMjpeg,  ///< Motion JPEG: one compressed JPEG image per frame, variable size.
    kZ16,    ///< 16-bit little-endian depth in device units (see the device's depth unit).
};

/// "grey8", "yuyv", "mjpeg", "z16".
std::string_view to_string(PixelFormat format);

/// Parses the names of `to_string`; kInvalidArgument otherwise.
Expected<PixelFormat> parse_pixel_format(std::string_view name);

/// Bytes per pixel of an uncompressed format; 0 for MJPEG.
std::size_t bytes_per_pixel(PixelFormat format);

/// One image. Not thread-safe for concurrent modification (a plain value).
struct Frame {
    int width = 0;
    int height = 0;
    PixelFormat format = PixelFormat::kGrey8;
    std::size_t stride_bytes = 0;             ///< Bytes per row; 0 for MJPEG.
    std::uint64_t sequence = 0;               ///< Counter of the device, from 0.
    std::chrono::nanoseconds timestamp_ns{};  ///< Capture time, steady clock of the host.
    std::vector<std::uint8_t> data;           ///< stride_bytes * height bytes (MJPEG: any).

    /// Depth sample (Z16 only) at (row, col), device units.
    std::uint16_t z16_at(int row, int col) const {
        const std::size_t at = static_cast<std::size_t>(row) * stride_bytes + 2u * col;
        return static_cast<std::uint16_t>(data[at] | (data[at + 1] << 8));
    }
};

/// Checks that the buffer is as long as the format and geometry say; `source` names the
/// device or file in the message (kFormat).
Expected<void> check_frame(const Frame& frame, std::string_view source);

}  // namespace anascan::drivers
