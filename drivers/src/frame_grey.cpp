#include "frame_grey.hpp"

#include <opencv2/imgproc.hpp>
#include <string>

#include "anascan/drivers/grey_image.hpp"

namespace anascan::drivers {

Expected<cv::Mat> frame_to_grey(const Frame& frame, std::string_view source) {
    if (auto ok = check_frame(frame, source); !ok) return fail(ok.error());
    auto* data = const_cast<std::uint8_t*>(frame.data.data());  // wrapped read-only
    switch (frame.format) {
        case PixelFormat::kGrey8:
            return cv::Mat(frame.height, frame.width, CV_8UC1, data, frame.stride_bytes).clone();
        case PixelFormat::kYuyv: {
            cv::Mat grey;
            cv::cvtColor(cv::Mat(frame.height, frame.width, CV_8UC2, data, frame.stride_bytes),
                         grey, cv::COLOR_YUV2GRAY_YUYV);
            return grey;
        }
        case PixelFormat::kMjpeg: {
            cv::Mat grey;
            const bool decoded = bool(decode_grey_image(frame.data, source, grey));
            if (!decoded || grey.cols != frame.width || grey.rows != frame.height)
                return fail(ErrorCode::kFormat, std::string(source) + ": frame " +
                                                    std::to_string(frame.sequence) + " is not a " +
                                                    std::to_string(frame.width) + " x " +
                                                    std::to_string(frame.height) + " JPEG image");
            return grey;
        }
        case PixelFormat::kZ16:
            break;
    }
    return fail(ErrorCode::kFormat, std::string(source) +
                                        ": a structured-light camera must deliver grey images, "
                                        "not z16 depth");
}

}  // namespace anascan::drivers
