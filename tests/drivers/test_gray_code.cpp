#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <opencv2/core.hpp>
#include <opencv2/structured_light.hpp>

#include "anascan/drivers/structured_light/gray_code.hpp"
#include "sl_synthetic.hpp"

namespace anascan::drivers::sl {
namespace {

TEST(GrayCodeLayout, CountsOpenCvImages) {
    const GrayCodeLayout layout{.projector_width_px = 1280, .projector_height_px = 800};
    EXPECT_EQ(layout.column_bits(), 11);
    EXPECT_EQ(layout.row_bits(), 10);
    EXPECT_EQ(layout.image_count(), 44);
}

// Our patterns are OpenCV's GrayCodePattern::generate output, then white and black.
TEST(GrayCodePatterns, EqualOpenCvGenerate) {
    const GrayCodeLayout layout{.projector_width_px = 1280, .projector_height_px = 800};
    cv::structured_light::GrayCodePattern::Params params;
    params.width = layout.projector_width_px;
    params.height = layout.projector_height_px;
    std::vector<cv::Mat> expected;
    ASSERT_TRUE(cv::structured_light::GrayCodePattern::create(params)->generate(expected));
    cv::Mat white, black;
    cv::structured_light::GrayCodePattern::create(params)->getImagesForShadowMasks(black, white);
    expected.push_back(white);
    expected.push_back(black);
    const std::vector<cv::Mat> ours = make_gray_code_patterns(layout);
    ASSERT_EQ(ours.size(), expected.size());
    for (std::size_t i = 0; i < ours.size(); ++i)
        EXPECT_EQ(cv::norm(ours[i], expected[i], cv::NORM_INF), 0.0) << "image " << i + 1;
}

struct Decoded {
    test::SyntheticRig rig = test::make_rig();
    ProjectorMap map;
};

Decoded decode_rendered(const test::RenderOptions& render, const GrayCodeDecodeConfig& config,
                        const std::function<void(std::vector<cv::Mat>&)>& corrupt = {}) {
    Decoded d;
    std::vector<cv::Mat> images =
        test::render(d.rig, 1, make_gray_code_patterns(d.rig.projector), render);
    if (corrupt) corrupt(images);
    auto map = decode_gray_code(images, d.rig.projector, config);
    EXPECT_TRUE(map) << map.error().message;
    if (map) d.map = *map;
    return d;
}

bool inside(const GrayCodeLayout& p, const Eigen::Vector2d& uv, double margin) {
    return uv.x() > -0.5 + margin && uv.y() > -0.5 + margin &&
           uv.x() < p.projector_width_px - 0.5 - margin &&
           uv.y() < p.projector_height_px - 0.5 - margin;
}

// One sample per pixel of the nearest projector pixel: every lit pixel decodes to exactly
// the projector pixel it sees.
TEST(GrayCodeDecode, IntegerCodesExact) {
    const Decoded d = decode_rendered({}, {.subpixel = false});
    std::size_t lit = 0;
    for (int y = 0; y < d.map.contrast.rows; ++y) {
        for (int x = 0; x < d.map.contrast.cols; ++x) {
            const Eigen::Vector2d uv = test::projector_coordinates(d.rig, 1, x, y);
            if (!inside(d.rig.projector, uv, 0.0)) {
                EXPECT_FALSE(d.map.valid(x, y)) << x << "," << y;
                continue;
            }
            ++lit;
            ASSERT_TRUE(d.map.valid(x, y)) << x << "," << y;
            EXPECT_EQ(d.map.column_px.at<float>(y, x), std::floor(uv.x() + 0.5)) << x << "," << y;
            EXPECT_EQ(d.map.row_px.at<float>(y, x), std::floor(uv.y() + 0.5)) << x << "," << y;
        }
    }
    EXPECT_GT(lit, 100000u);
    EXPECT_EQ(d.map.valid_count, lit);
}

// Projector optics that blur each edge over one projector pixel (bilinear) and area-sampled
// camera pixels: the sub-pixel position is far closer to the truth than the integer code.
TEST(GrayCodeDecode, SubpixelBeatsInteger) {
    const test::SyntheticRig rig = test::make_rig();
    const std::vector<cv::Mat> images = test::render(rig, 1, make_gray_code_patterns(rig.projector),
                                                     {.supersample = 2, .bilinear = true});
    Decoded sub, whole;
    sub.map = decode_gray_code(images, rig.projector, {.subpixel = true}).value();
    whole.map = decode_gray_code(images, rig.projector, {.subpixel = false}).value();
    double sub_error = 0.0, whole_error = 0.0;
    std::size_t n = 0;
    for (int y = 0; y < sub.map.contrast.rows; ++y) {
        for (int x = 0; x < sub.map.contrast.cols; ++x) {
            if (!sub.map.valid(x, y) || !whole.map.valid(x, y)) continue;
            const Eigen::Vector2d uv = test::projector_coordinates(sub.rig, 1, x, y);
            sub_error += std::abs(sub.map.column_px.at<float>(y, x) - uv.x());
            whole_error += std::abs(whole.map.column_px.at<float>(y, x) - uv.x());
            ++n;
        }
    }
    ASSERT_GT(n, 100000u);
    std::printf("mean |column error|: sub-pixel %.3f px, integer %.3f px\n", sub_error / n,
                whole_error / n);
    EXPECT_LT(sub_error / n, 0.3 * whole_error / n);
    EXPECT_LT(sub_error / n, 0.06);  // Integer codes: ~0.25 px mean error.
}

TEST(GrayCodeDecode, LowContrastIsInvalid) {
    const Decoded d = decode_rendered({}, {}, [](std::vector<cv::Mat>& images) {
        images[images.size() - 2](cv::Rect(300, 200, 20, 20)).setTo(30);  // white ~ black
    });
    for (int y = 200; y < 220; ++y)
        for (int x = 300; x < 320; ++x) EXPECT_FALSE(d.map.valid(x, y));
    EXPECT_TRUE(d.map.valid(280, 210));
}

// A most significant bit with pattern == inverse cannot be a border bit: rejected.
TEST(GrayCodeDecode, AmbiguousBitIsInvalid) {
    const Decoded d = decode_rendered({}, {}, [](std::vector<cv::Mat>& images) {
        images[1](cv::Rect(300, 200, 20, 20)).copyTo(images[0](cv::Rect(300, 200, 20, 20)));
    });
    for (int y = 200; y < 220; ++y)
        for (int x = 300; x < 320; ++x) EXPECT_FALSE(d.map.valid(x, y));
    EXPECT_TRUE(d.map.valid(280, 210));
}

TEST(GrayCodeDecode, RejectsBadSequences) {
    const GrayCodeLayout layout{.projector_width_px = 64, .projector_height_px = 32};
    std::vector<cv::Mat> images(std::size_t(layout.image_count()), cv::Mat(8, 8, CV_8UC1, 0.0));
    std::vector<cv::Mat> few(images.begin(), images.end() - 1);
    auto r = decode_gray_code(few, layout, {});
    ASSERT_FALSE(r);
    EXPECT_NE(r.error().message.find("23 images, expected 24"), std::string::npos)
        << r.error().message;
    images[5] = cv::Mat(8, 9, CV_8UC1, 0.0);
    r = decode_gray_code(images, layout, {});
    ASSERT_FALSE(r);
    EXPECT_NE(r.error().message.find("image 6 is 9x8 px"), std::string::npos) << r.error().message;
    images[5] = cv::Mat(8, 8, CV_8UC3, cv::Scalar::all(0));
    r = decode_gray_code(images, layout, {});
    ASSERT_FALSE(r);
    EXPECT_NE(r.error().message.find("image 6 is not 8-bit grey"), std::string::npos);
}

}  // namespace
}  // namespace anascan::drivers::sl
