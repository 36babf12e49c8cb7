#pragma once
/// \file
/// Gray-code structured light in the layout of OpenCV's structured_light::GrayCodePattern:
/// column codes, then row codes, most significant bit first, each pattern followed by its
/// inverse, then an all-white and an all-black image. Pattern bit = Gray code bit of the
/// projector column (row); bright (255) means 1.

#include <cstdint>
#include <opencv2/core/mat.hpp>
#include <span>
#include <string>
#include <vector>

#include "anascan/processing/core/expected.hpp"

namespace anascan::drivers::sl {

/// Projector resolution and the image count it implies.
struct GrayCodeLayout {
    int projector_width_px = 1280;
    int projector_height_px = 800;

    int column_bits() const;  ///< ceil(log2(width)): 11 for 1280.
    int row_bits() const;     ///< ceil(log2(height)): 10 for 800.
    int image_count() const { return 2 * (column_bits() + row_bits()) + 2; }
    int white_index() const { return image_count() - 2; }
    int black_index() const { return image_count() - 1; }
};

/// The projector images (CV_8UC1, projector size) in capture order.
std::vector<cv::Mat> make_gray_code_patterns(const GrayCodeLayout& layout);

/// Per-pixel validity rules of the decoder.
struct GrayCodeDecodeConfig {
    int min_contrast = 40;     ///< White minus black, grey levels; below: shadow or dark.
    int min_bit_contrast = 5;  ///< |pattern - inverse|, grey levels, for a bit to be certain.
    bool subpixel = true;      ///< Interpolate inside the decoded projector pixel.
};

/// Decoded projector coordinates of every camera pixel.
///
/// Projector pixel centres are at integer coordinates (OpenCV convention): pixel c covers
/// [c - 0.5, c + 0.5). Invalid pixels hold NaN in both maps and 0 in `contrast`.
struct ProjectorMap {
    cv::Mat column_px;  ///< CV_32FC1, camera size.
    cv::Mat row_px;     ///< CV_32FC1, camera size.
    cv::Mat contrast;   ///< CV_8UC1 white minus black, grey levels (0 where invalid).
    cv::Mat white;      ///< CV_8UC1 the all-white image (texture), shared with the input.
    std::size_t valid_count = 0;

    bool valid(int x, int y) const { return contrast.at<std::uint8_t>(y, x) != 0; }
};

/// Decodes one camera's Gray-code images (CV_8UC1, all the same size, `layout.image_count()`
/// of them). A pixel is valid when white - black >= min_contrast, its code lies inside the
/// projector, and every bit is certain except the two that flip at the borders of its
/// projector pixel (those carry the sub-pixel position: u = c + (a - b) / (2 max(a, b)) with
/// a, b the |pattern - inverse| of the left and right border bits; docs/structured-light.md).
/// Thread-safe; runs a TBB loop over rows; the result does not depend on the thread count.
Expected<ProjectorMap> decode_gray_code(std::span<const cv::Mat> images,
                                        const GrayCodeLayout& layout,
                                        const GrayCodeDecodeConfig& config);

/// Checks count, type (CV_8UC1) and equal sizes; `what` names the sequence in messages.
Expected<void> check_image_sequence(std::span<const cv::Mat> images, std::size_t expected_count,
                                    const std::string& what);

}  // namespace anascan::drivers::sl
