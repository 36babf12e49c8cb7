#pragma once
/// \file
/// 8-bit grey images in the formats cameras and captures come in: JPEG (libjpeg-turbo) and
/// PNG (libpng), read and PNG written. Not OpenCV's imgcodecs: loading that library (GDAL,
/// DICOM, HEIF and 130 others behind it) took 0.11 s of every command's start
/// (docs/structured-light.md, "Speed").

#include <cstdint>
#include <filesystem>
#include <opencv2/core/mat.hpp>
#include <span>
#include <string_view>

#include "anascan/processing/core/expected.hpp"

namespace anascan::drivers {

/// Decodes a JPEG or PNG image (grey or colour, 8 or 16 bits) as 8-bit grey: JPEG decodes
/// its luma only, colour PNG is converted to luminance, 16 bits keep their high byte.
/// Writes into `image` in place when it already is 8-bit grey of the image's size, else
/// (re)allocates it. kFormat error starting with `name` on anything else: another format,
/// a corrupt or truncated file, more than 2^28 pixels.
Expected<void> decode_grey_image(std::span<const std::uint8_t> bytes, std::string_view name,
                                 cv::Mat& image);

/// Reads `file` and decodes it as above; kIo error naming the file when it cannot be read
/// ("no such file" when it does not exist).
Expected<void> read_grey_image(const std::filesystem::path& file, cv::Mat& image);

/// Writes an 8-bit grey image as PNG (fast compression). kIo error naming the file.
Expected<void> write_grey_png(const std::filesystem::path& file, const cv::Mat& grey);

}  // namespace anascan::drivers
