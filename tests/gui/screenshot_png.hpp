#pragma once
// Reads the field app's screenshots as OpenCV's imread(IMREAD_COLOR) would (BGR, 8 bits),
// through libpng: OpenCV's imgcodecs registers GDAL, whose own mutexes ThreadSanitizer
// reports as a lock-order inversion, and the app itself writes with libpng.
#include <png.h>

#include <filesystem>
#include <opencv2/core/mat.hpp>

namespace anascan::field::test {

/// The image, or an empty Mat when the file is missing or not a PNG.
inline cv::Mat read_screenshot(const std::filesystem::path& file) {
    png_image png{};
    png.version = PNG_IMAGE_VERSION;
    if (png_image_begin_read_from_file(&png, file.c_str()) == 0) return {};
    png.format = PNG_FORMAT_BGR;
    cv::Mat image(int(png.height), int(png.width), CV_8UC3);
    if (png_image_finish_read(&png, nullptr, image.data, png_int_32(image.step), nullptr) == 0)
        return {};
    return image;
}

}  // namespace anascan::field::test
