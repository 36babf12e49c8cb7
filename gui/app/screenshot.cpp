#include "screenshot.hpp"

#include <GL/gl.h>
#include <png.h>

#include <vector>

namespace anascan::field {

Expected<void> write_screenshot(const std::filesystem::path& path, int width_px, int height_px) {
    if (width_px <= 0 || height_px <= 0) {
        return fail(ErrorCode::kInvalidArgument, path.string() + ": empty frame buffer");
    }
    std::vector<unsigned char> rgb(std::size_t(width_px) * std::size_t(height_px) * 3);
    glPixelStorei(GL_PACK_ALIGNMENT, 1);
    glReadBuffer(GL_BACK);
    glReadPixels(0, 0, width_px, height_px, GL_RGB, GL_UNSIGNED_BYTE, rgb.data());
    png_image png{};
    png.version = PNG_IMAGE_VERSION;
    png.width = png_uint_32(width_px);
    png.height = png_uint_32(height_px);
    png.format = PNG_FORMAT_RGB;
    // OpenGL's row 0 is the bottom: a negative stride hands libpng the rows top first.
    const png_int_32 stride = -png_int_32(width_px) * 3;
    if (png_image_write_to_file(&png, path.c_str(), 0, rgb.data(), stride, nullptr) == 0) {
        return fail(ErrorCode::kIo,
                    path.string() + ": cannot write the screenshot: " + png.message);
    }
    return {};
}

}  // namespace anascan::field
