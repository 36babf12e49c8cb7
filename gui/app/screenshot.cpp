#include "screenshot.hpp"

#include <GL/gl.h>

#include <opencv2/core.hpp>
#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>

namespace anascan::field {

Expected<void> write_screenshot(const std::filesystem::path& path, int width_px, int height_px) {
    if (width_px <= 0 || height_px <= 0) {
        return fail(ErrorCode::kInvalidArgument, path.string() + ": empty frame buffer");
    }
    cv::Mat rgb(height_px, width_px, CV_8UC3);
    glPixelStorei(GL_PACK_ALIGNMENT, 1);
    glReadBuffer(GL_BACK);
    glReadPixels(0, 0, width_px, height_px, GL_RGB, GL_UNSIGNED_BYTE, rgb.data);
    cv::Mat bgr;
    cv::cvtColor(rgb, bgr, cv::COLOR_RGB2BGR);
    cv::flip(bgr, bgr, 0);  // OpenGL's row 0 is the bottom
    bool written = false;
    try {
        written = cv::imwrite(path.string(), bgr);
    } catch (const cv::Exception& e) {
        return fail(ErrorCode::kIo, path.string() + ": cannot write the screenshot: " + e.what());
    }
    if (!written) {
        return fail(ErrorCode::kIo, path.string() + ": cannot write the screenshot");
    }
    return {};
}

}  // namespace anascan::field
