// libFuzzer harness for the grey image reader (JPEG through libjpeg-turbo, PNG through
// libpng): any input gives either an 8-bit grey image of at most 2^28 pixels, decoded the
// same way again in place, or an error naming the source.
#include <cstddef>
#include <cstdint>
#include <cstdlib>
#include <cstring>
#include <span>

#include "anascan/drivers/grey_image.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    const std::span<const std::uint8_t> bytes(data, size);
    cv::Mat image;
    const auto decoded = anascan::drivers::decode_grey_image(bytes, "fuzz.img", image);
    if (!decoded) {
        if (decoded.error().message.rfind("fuzz.img: not a readable image (", 0) != 0) std::abort();
        return 0;
    }
    if (image.empty() || image.type() != CV_8UC1) std::abort();
    if (std::uint64_t(image.total()) > (std::uint64_t(1) << 28)) std::abort();
    const cv::Mat first = image.clone();
    const std::uint8_t* buffer = image.data;
    if (!anascan::drivers::decode_grey_image(bytes, "again.img", image)) std::abort();
    if (image.data != buffer) std::abort();  // same size: decoded in place
    if (std::memcmp(first.data, image.data, first.total()) != 0) std::abort();
    return 0;
}
