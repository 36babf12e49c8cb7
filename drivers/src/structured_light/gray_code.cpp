#include "anascan/drivers/structured_light/gray_code.hpp"

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <bit>
#include <cmath>
#include <cstdint>
#include <cstdlib>
#include <limits>
#include <opencv2/core.hpp>

namespace anascan::drivers::sl {
namespace {

int bits_for(int size) { return size <= 1 ? 1 : std::bit_width(static_cast<unsigned>(size - 1)); }

std::uint32_t gray_to_binary(std::uint32_t g) {
    for (std::uint32_t shift = 1; shift < 32; shift <<= 1) g ^= g >> shift;
    return g;
}

/// One axis of the code: its first image and bit count, and the projector size along it.
struct Axis {
    int first_image = 0;
    int bits = 0;
    int size_px = 0;
};

/// Bit planes of one axis along one image row, packed per pixel (MSB = first pattern).
struct PackedRow {
    std::vector<std::uint16_t> gray;       ///< Gray code from pattern > inverse.
    std::vector<std::uint16_t> uncertain;  ///< Bits with |pattern - inverse| < min.
    std::vector<std::uint8_t> magnitude;   ///< |pattern - inverse| per bit: [bit][x].
};

void pack_row(std::span<const cv::Mat> images, const Axis& axis, int y, int min_bit_contrast,
              PackedRow& p) {
    const int width = images[0].cols;
    p.gray.assign(std::size_t(width), 0);
    p.uncertain.assign(std::size_t(width), 0);
    p.magnitude.resize(std::size_t(axis.bits) * width);
    for (int m = 0; m < axis.bits; ++m) {
        const std::uint8_t* pattern = images[axis.first_image + 2 * m].ptr<std::uint8_t>(y);
        const std::uint8_t* inverse = images[axis.first_image + 2 * m + 1].ptr<std::uint8_t>(y);
        // Local restrict pointers: uint8 stores could alias the vectors' members otherwise,
        // which keeps the compiler from vectorising.
        std::uint8_t* __restrict mag = p.magnitude.data() + std::size_t(m) * width;
        std::uint16_t* __restrict gray = p.gray.data();
        std::uint16_t* __restrict uncertain = p.uncertain.data();
        for (int x = 0; x < width; ++x) {
            const int d = int(pattern[x]) - int(inverse[x]);
            const int a = d < 0 ? -d : d;
            mag[x] = std::uint8_t(a);
            gray[x] = std::uint16_t((gray[x] << 1) | (d > 0 ? 1 : 0));
            uncertain[x] = std::uint16_t((uncertain[x] << 1) | (a < min_bit_contrast ? 1 : 0));
        }
    }
}

/// Decodes one axis along image row y into out[x] (projector coordinate or NaN).
/// `ok[x]` says whether the pixel passed the contrast test.
void decode_axis_row(std::span<const cv::Mat> images, const Axis& axis, int y,
                     const std::uint8_t* ok, const GrayCodeDecodeConfig& config, PackedRow& p,
                     float* out) {
    const int width = images[0].cols;
    pack_row(images, axis, y, config.min_bit_contrast, p);
    constexpr float kNaN = std::numeric_limits<float>::quiet_NaN();
    const auto magnitude = [&](int bit, int x) {
        return int(p.magnitude[std::size_t(axis.bits - 1 - bit) * width + x]);
    };
    for (int x = 0; x < width; ++x) {
        out[x] = kNaN;
        if (!ok[x]) continue;
        const std::uint32_t c = gray_to_binary(p.gray[x]);
        if (c >= std::uint32_t(axis.size_px)) continue;
        // Exactly one Gray bit flips between neighbouring codes: bit ctz(c) between c-1 and
        // c, bit ctz(c+1) between c and c+1. Only those two may be uncertain.
        const int left = c > 0 ? std::countr_zero(c) : -1;
        const int right = c + 1 < std::uint32_t(axis.size_px) ? std::countr_zero(c + 1) : -1;
        const std::uint32_t border =
            (left >= 0 ? 1u << left : 0u) | (right >= 0 ? 1u << right : 0u);
        if (p.uncertain[x] & ~border) continue;
        float position = float(c);
        if (config.subpixel && left >= 0 && right >= 0) {
            // The border bits' |pattern - inverse| fall linearly to zero at the projector
            // pixel's borders over half a projector pixel (a one-pixel ramp between pixel
            // centres) and saturate inside: the unsaturated one, relative to the saturated
            // one, gives the distance to its border (docs/structured-light.md).
            const int a = magnitude(left, x);
            const int b = magnitude(right, x);
            if (a + b < config.min_bit_contrast) continue;
            position += 0.5f * float(a - b) / float(std::max(a, b));
        }
        out[x] = position;
    }
}

void decode_row(std::span<const cv::Mat> images, const GrayCodeLayout& layout, int y,
                const GrayCodeDecodeConfig& config, PackedRow& packed, ProjectorMap& map) {
    const int width = images[0].cols;
    const std::uint8_t* white = images[layout.white_index()].ptr<std::uint8_t>(y);
    const std::uint8_t* black = images[layout.black_index()].ptr<std::uint8_t>(y);
    std::uint8_t* contrast = map.contrast.ptr<std::uint8_t>(y);
    for (int x = 0; x < width; ++x) {
        const int c = int(white[x]) - int(black[x]);
        contrast[x] = c >= config.min_contrast ? std::uint8_t(c) : 0;
    }
    const Axis columns{0, layout.column_bits(), layout.projector_width_px};
    const Axis rows{2 * layout.column_bits(), layout.row_bits(), layout.projector_height_px};
    float* col = map.column_px.ptr<float>(y);
    float* row = map.row_px.ptr<float>(y);
    decode_axis_row(images, columns, y, contrast, config, packed, col);
    decode_axis_row(images, rows, y, contrast, config, packed, row);
    for (int x = 0; x < width; ++x) {
        if (std::isnan(col[x]) || std::isnan(row[x])) {
            col[x] = row[x] = std::numeric_limits<float>::quiet_NaN();
            contrast[x] = 0;
        }
    }
}

}  // namespace

int GrayCodeLayout::column_bits() const { return bits_for(projector_width_px); }
int GrayCodeLayout::row_bits() const { return bits_for(projector_height_px); }

std::vector<cv::Mat> make_gray_code_patterns(const GrayCodeLayout& layout) {
    const int w = layout.projector_width_px;
    const int h = layout.projector_height_px;
    std::vector<cv::Mat> patterns;
    const auto add_axis = [&](int bits, bool along_columns) {
        for (int m = 0; m < bits; ++m) {
            cv::Mat pattern(h, w, CV_8UC1);
            for (int y = 0; y < h; ++y) {
                for (int x = 0; x < w; ++x) {
                    const unsigned v = unsigned(along_columns ? x : y);
                    const unsigned gray = v ^ (v >> 1);
                    pattern.at<std::uint8_t>(y, x) = ((gray >> (bits - 1 - m)) & 1u) ? 255 : 0;
                }
            }
            patterns.push_back(pattern);
            patterns.push_back(255 - pattern);
        }
    };
    add_axis(layout.column_bits(), true);
    add_axis(layout.row_bits(), false);
    patterns.push_back(cv::Mat(h, w, CV_8UC1, cv::Scalar(255)));
    patterns.push_back(cv::Mat(h, w, CV_8UC1, cv::Scalar(0)));
    return patterns;
}

Expected<void> check_image_sequence(std::span<const cv::Mat> images, std::size_t expected_count,
                                    const std::string& what) {
    if (images.size() != expected_count) {
        return fail(ErrorCode::kInvalidArgument, what + ": " + std::to_string(images.size()) +
                                                     " images, expected " +
                                                     std::to_string(expected_count));
    }
    for (std::size_t i = 0; i < images.size(); ++i) {
        const cv::Mat& im = images[i];
        if (im.empty() || im.type() != CV_8UC1) {
            return fail(ErrorCode::kInvalidArgument,
                        what + ": image " + std::to_string(i + 1) + " is not 8-bit grey");
        }
        if (im.size() != images[0].size()) {
            return fail(ErrorCode::kInvalidArgument,
                        what + ": image " + std::to_string(i + 1) + " is " +
                            std::to_string(im.cols) + "x" + std::to_string(im.rows) +
                            " px, image 1 is " + std::to_string(images[0].cols) + "x" +
                            std::to_string(images[0].rows) + " px");
        }
    }
    return {};
}

Expected<ProjectorMap> decode_gray_code(std::span<const cv::Mat> images,
                                        const GrayCodeLayout& layout,
                                        const GrayCodeDecodeConfig& config) {
    if (layout.projector_width_px < 2 || layout.projector_height_px < 2 ||
        layout.column_bits() > 16 || layout.row_bits() > 16 || config.min_contrast < 1)
        return fail(ErrorCode::kInvalidArgument,
                    "Gray code: projector size must be 2..65536 px, min contrast >= 1");
    if (auto ok = check_image_sequence(images, std::size_t(layout.image_count()), "Gray code"); !ok)
        return fail(ok.error());
    const cv::Size size = images[0].size();
    ProjectorMap map{.column_px = cv::Mat(size, CV_32FC1),
                     .row_px = cv::Mat(size, CV_32FC1),
                     .contrast = cv::Mat(size, CV_8UC1),
                     .white = images[layout.white_index()]};
    tbb::parallel_for(tbb::blocked_range<int>(0, size.height, 16),
                      [&](const tbb::blocked_range<int>& r) {
                          PackedRow packed;  // Scratch, reused over the block's rows.
                          for (int y = r.begin(); y < r.end(); ++y)
                              decode_row(images, layout, y, config, packed, map);
                      });
    map.valid_count = std::size_t(cv::countNonZero(map.contrast));
    return map;
}

}  // namespace anascan::drivers::sl
