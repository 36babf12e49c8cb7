#include <gtest/gtest.h>

#include <cmath>

#include "anascan/drivers/structured_light/stereo_decoder.hpp"
#include "sl_synthetic.hpp"

namespace anascan::drivers::sl {
namespace {

// Gray code + 4-step phase shift through bilinear projector optics: the phase coordinates
// are within a few hundredths of a projector pixel of the truth.
TEST(PhaseShift, DecodesSubpixelCoordinates) {
    const test::SyntheticRig rig = test::make_rig();
    const PatternSequence sequence{.gray = rig.projector, .phase = PhaseShiftLayout{}};
    const std::vector<cv::Mat> patterns = make_patterns(sequence);
    ASSERT_EQ(patterns.size(), sequence.image_count());
    const auto images = test::render(rig, 1, patterns, {.supersample = 2, .bilinear = true});
    auto map = decode_camera(images, sequence, {.sequence = sequence});
    ASSERT_TRUE(map) << map.error().message;
    std::vector<double> errors;
    for (int y = 0; y < map->contrast.rows; ++y) {
        for (int x = 0; x < map->contrast.cols; ++x) {
            if (!map->valid(x, y)) continue;
            const Eigen::Vector2d uv = test::projector_coordinates(rig, 1, x, y);
            errors.push_back(std::abs(map->column_px.at<float>(y, x) - uv.x()));
            errors.push_back(std::abs(map->row_px.at<float>(y, x) - uv.y()));
        }
    }
    ASSERT_GT(errors.size(), 200000u);
    std::sort(errors.begin(), errors.end());
    EXPECT_LT(errors[errors.size() * 95 / 100], 0.06);
}

TEST(PhaseShift, RejectsWrongImageCount) {
    ProjectorMap map;
    map.column_px = cv::Mat(4, 4, CV_32FC1, 0.0);
    std::vector<cv::Mat> images(7, cv::Mat(4, 4, CV_8UC1, 0.0));
    auto r = refine_with_phase_shift(map, images, {}, {});
    ASSERT_FALSE(r);
    EXPECT_NE(r.error().message.find("7 images, expected 8"), std::string::npos);
}

}  // namespace
}  // namespace anascan::drivers::sl
