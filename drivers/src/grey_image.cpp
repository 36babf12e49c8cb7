#include "anascan/drivers/grey_image.hpp"

// clang-format off
#include <cstdio>   // jpeglib.h needs FILE and size_t first
#include <jpeglib.h>
#include <jerror.h>
// clang-format on
#include <png.h>

#include <csetjmp>
#include <cstring>
#include <fstream>
#include <string>
#include <vector>

namespace anascan::drivers {
namespace {

constexpr std::uint64_t kMaxPixels = std::uint64_t(1) << 28;

Error format_error(std::string_view name, std::string_view what) {
    return {ErrorCode::kFormat,
            std::string(name) + ": not a readable image (" + std::string(what) + ")"};
}

bool fits(std::uint64_t width, std::uint64_t height) {
    return width > 0 && height > 0 && width * height <= kMaxPixels;
}

/// Gives `image` the size as 8-bit grey, keeping its buffer when it already has it.
void shape(cv::Mat& image, int width, int height) {
    if (image.cols != width || image.rows != height || image.type() != CV_8UC1)
        image.create(height, width, CV_8UC1);
}

struct JpegFailure {
    jpeg_error_mgr manager;
    std::jmp_buf jump;
    char message[JMSG_LENGTH_MAX];
};

[[noreturn]] void on_jpeg_error(j_common_ptr info) {
    auto* failure = reinterpret_cast<JpegFailure*>(info->err);
    (*info->err->format_message)(info, failure->message);
    std::longjmp(failure->jump, 1);
}

/// Warnings pass, except a file that ends early: libjpeg would fill the rest with grey.
void on_jpeg_message(j_common_ptr info, int level) {
    if (level < 0 && info->err->msg_code == JWRN_JPEG_EOF) on_jpeg_error(info);
}

/// No object with a destructor lives in this frame: a libjpeg error longjmps out of it.
bool decode_jpeg(std::span<const std::uint8_t> bytes, cv::Mat& image, JpegFailure& failure) {
    jpeg_decompress_struct info{};
    info.err = jpeg_std_error(&failure.manager);
    failure.manager.error_exit = on_jpeg_error;
    failure.manager.emit_message = on_jpeg_message;
    if (setjmp(failure.jump) != 0) {
        jpeg_destroy_decompress(&info);
        return false;
    }
    jpeg_create_decompress(&info);
    jpeg_mem_src(&info, bytes.data(), static_cast<unsigned long>(bytes.size()));
    jpeg_read_header(&info, TRUE);
    if (!fits(info.image_width, info.image_height)) {
        std::snprintf(failure.message, sizeof(failure.message), "%u x %u pixels is too large",
                      info.image_width, info.image_height);
        jpeg_destroy_decompress(&info);
        return false;
    }
    info.out_color_space = JCS_GRAYSCALE;
    jpeg_start_decompress(&info);
    shape(image, int(info.output_width), int(info.output_height));
    while (info.output_scanline < info.output_height) {
        JSAMPROW row = image.ptr<std::uint8_t>(int(info.output_scanline));
        jpeg_read_scanlines(&info, &row, 1);
    }
    jpeg_finish_decompress(&info);
    jpeg_destroy_decompress(&info);
    return true;
}

Expected<void> decode_png(std::span<const std::uint8_t> bytes, std::string_view name,
                          cv::Mat& image) {
    png_image png{};
    png.version = PNG_IMAGE_VERSION;
    if (png_image_begin_read_from_memory(&png, bytes.data(), bytes.size()) == 0)
        return fail(format_error(name, std::string("PNG: ") + png.message));
    if (!fits(png.width, png.height)) {
        png_image_free(&png);
        return fail(format_error(name, "PNG: " + std::to_string(png.width) + " x " +
                                           std::to_string(png.height) + " pixels is too large"));
    }
    const bool sixteen = (png.format & PNG_FORMAT_FLAG_LINEAR) != 0;
    shape(image, int(png.width), int(png.height));
    int ok = 0;
    if (sixteen) {
        // Linear 16-bit luminance, then the high byte: as OpenCV's grey reading does it.
        png.format = PNG_FORMAT_LINEAR_Y;
        std::vector<std::uint16_t> wide(std::size_t(png.width) * png.height);
        ok = png_image_finish_read(&png, nullptr, wide.data(), 0, nullptr);
        for (int y = 0; ok != 0 && y < image.rows; ++y) {
            const std::uint16_t* in = wide.data() + std::size_t(y) * png.width;
            std::uint8_t* out = image.ptr<std::uint8_t>(y);
            for (int x = 0; x < image.cols; ++x) out[x] = std::uint8_t(in[x] >> 8);
        }
    } else {
        png.format = PNG_FORMAT_GRAY;
        ok = png_image_finish_read(&png, nullptr, image.data, png_int_32(image.step), nullptr);
    }
    if (ok == 0) return fail(format_error(name, std::string("PNG: ") + png.message));
    return {};
}

bool is_jpeg(std::span<const std::uint8_t> b) {
    return b.size() >= 3 && b[0] == 0xFF && b[1] == 0xD8 && b[2] == 0xFF;
}

bool is_png(std::span<const std::uint8_t> b) {
    static constexpr std::uint8_t kSignature[8] = {0x89, 'P', 'N', 'G', '\r', '\n', 0x1A, '\n'};
    return b.size() >= 8 && std::memcmp(b.data(), kSignature, 8) == 0;
}

}  // namespace

Expected<void> decode_grey_image(std::span<const std::uint8_t> bytes, std::string_view name,
                                 cv::Mat& image) {
    if (is_png(bytes)) return decode_png(bytes, name, image);
    if (!is_jpeg(bytes)) return fail(format_error(name, "neither JPEG nor PNG"));
    JpegFailure failure{};
    if (!decode_jpeg(bytes, image, failure))
        return fail(format_error(name, std::string("JPEG: ") + failure.message));
    return {};
}

Expected<void> read_grey_image(const std::filesystem::path& file, cv::Mat& image) {
    thread_local std::vector<std::uint8_t> bytes;
    std::ifstream in(file, std::ios::binary | std::ios::ate);
    if (!in) {
        const bool exists = std::filesystem::exists(file);
        return fail(ErrorCode::kIo,
                    file.string() + (exists ? ": cannot be read" : ": no such file"));
    }
    const std::streamoff size = in.tellg();
    bytes.resize(std::size_t(std::max<std::streamoff>(size, 0)));
    in.seekg(0);
    if (!in.read(reinterpret_cast<char*>(bytes.data()), size))
        return fail(ErrorCode::kIo, file.string() + ": cannot be read");
    return decode_grey_image(bytes, file.string(), image);
}

Expected<void> write_grey_png(const std::filesystem::path& file, const cv::Mat& grey) {
    if (grey.type() != CV_8UC1 || grey.empty())
        return fail(ErrorCode::kInvalidArgument, file.string() + ": only 8-bit grey is written");
    png_image png{};
    png.version = PNG_IMAGE_VERSION;
    png.width = png_uint_32(grey.cols);
    png.height = png_uint_32(grey.rows);
    png.format = PNG_FORMAT_GRAY;
    png.flags = PNG_IMAGE_FLAG_FAST;
    if (png_image_write_to_file(&png, file.c_str(), 0, grey.data, png_int_32(grey.step), nullptr) ==
        0)
        return fail(ErrorCode::kIo, file.string() + ": cannot write the image: " + png.message);
    return {};
}

}  // namespace anascan::drivers
