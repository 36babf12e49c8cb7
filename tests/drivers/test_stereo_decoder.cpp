#include <gtest/gtest.h>
#include <tbb/global_control.h>

#include <cmath>
#include <cstdio>

#include "anascan/drivers/structured_light/stereo_decoder.hpp"
#include "sl_synthetic.hpp"

namespace anascan::drivers::sl {
namespace {

struct Capture {
    test::SyntheticRig rig = test::make_rig();
    std::vector<cv::Mat> cam1, cam2;
};

const Capture& capture() {
    static const Capture rendered = [] {
        Capture c;
        const auto patterns = make_gray_code_patterns(c.rig.projector);
        const test::RenderOptions options{.supersample = 2, .bilinear = true};
        c.cam1 = test::render(c.rig, 1, patterns, options);
        c.cam2 = test::render(c.rig, 2, patterns, options);
        return c;
    }();
    return rendered;
}

StereoDecodeConfig config_for(const test::SyntheticRig& rig) {
    StereoDecodeConfig config;
    config.sequence.gray = rig.projector;
    config.triangulation.max_ray_gap_m = 0.005;
    return config;
}

// Every point lies on the rendered plane, at the place cam1's pixel sees.
TEST(StereoDecode, PlaneIsReconstructed) {
    const Capture& c = capture();
    auto result = decode_stereo(c.cam1, c.cam2, c.rig.calibration, config_for(c.rig));
    ASSERT_TRUE(result) << result.error().message;
    ASSERT_GT(result->cloud.size(), 50000u);
    ASSERT_EQ(result->cam1_px.size(), result->cloud.size());
    ASSERT_TRUE(result->cloud.attributes_consistent());
    std::vector<double> plane, along;
    for (std::size_t i = 0; i < result->cloud.size(); ++i) {
        const Eigen::Vector3d p = result->cloud.positions[i].cast<double>();
        plane.push_back(std::abs(c.rig.plane_normal.dot(p) - c.rig.plane_offset_m));
        const cv::Point2i px = result->cam1_px[i];
        along.push_back((p - test::surface_point(c.rig, 1, px.x, px.y)).norm());
    }
    std::sort(plane.begin(), plane.end());
    std::sort(along.begin(), along.end());
    std::printf("%zu points; distance to the plane: median %.3f mm, 99 %% %.3f mm\n", plane.size(),
                plane[plane.size() / 2] * 1e3, plane[plane.size() * 99 / 100] * 1e3);
    // At 1 m with an 800 px focal length and a 0.2 m baseline, 0.1 camera px ~ 0.6 mm.
    EXPECT_LT(plane[plane.size() / 2], 0.1e-3);
    EXPECT_LT(plane[plane.size() * 99 / 100], 0.5e-3);
    EXPECT_LT(along[along.size() * 99 / 100], 3e-3);
    EXPECT_LT(result->median_ray_gap_m, 0.5e-3);  // Exact calibration: rays meet.
}

TEST(StereoDecode, SameResultOnOneThread) {
    const Capture& c = capture();
    auto a = decode_stereo(c.cam1, c.cam2, c.rig.calibration, config_for(c.rig));
    const tbb::global_control one_thread(tbb::global_control::max_allowed_parallelism, 1);
    auto b = decode_stereo(c.cam1, c.cam2, c.rig.calibration, config_for(c.rig));
    ASSERT_TRUE(a && b);
    ASSERT_EQ(a->cloud.size(), b->cloud.size());
    EXPECT_EQ(a->cloud.positions, b->cloud.positions);
}

TEST(StereoDecode, ClearErrors) {
    const Capture& c = capture();
    const StereoDecodeConfig config = config_for(c.rig);
    std::vector<cv::Mat> short_cam2(c.cam2.begin(), c.cam2.end() - 1);
    auto r = decode_stereo(c.cam1, short_cam2, c.rig.calibration, config);
    ASSERT_FALSE(r);
    EXPECT_NE(r.error().message.find("cam2: 35 images, expected 36"), std::string::npos)
        << r.error().message;
    StereoCalibration other = c.rig.calibration;
    other.cam1.width_px = 1920;
    r = decode_stereo(c.cam1, c.cam2, other, config);
    ASSERT_FALSE(r);
    EXPECT_NE(r.error().message.find("cam1 images are 640x480 px but the calibration is for 1920"),
              std::string::npos)
        << r.error().message;
    r = decode_stereo({}, c.cam2, c.rig.calibration, config);
    ASSERT_FALSE(r);
    EXPECT_EQ(r.error().code, ErrorCode::kEmpty);
}

}  // namespace
}  // namespace anascan::drivers::sl

namespace anascan::drivers::sl {
namespace {

// Gray code + phase shift through the whole pipeline, as the simulated scanner calls it.
TEST(StereoDecode, PhaseShiftPlane) {
    const test::SyntheticRig rig = test::make_rig();
    StereoDecodeConfig config = config_for(rig);
    config.sequence.phase = PhaseShiftLayout{.period_px = 16, .steps = 4};
    const auto patterns = make_patterns(config.sequence);
    const test::RenderOptions options{.supersample = 2, .bilinear = true};
    const auto cam1 = test::render(rig, 1, patterns, options);
    const auto cam2 = test::render(rig, 2, patterns, options);
    auto result = decode_stereo(cam1, cam2, rig.calibration, config);
    ASSERT_TRUE(result) << result.error().message;
    ASSERT_GT(result->cloud.size(), 50000u);
    std::vector<double> plane;
    for (const Eigen::Vector3f& p : result->cloud.positions)
        plane.push_back(std::abs(rig.plane_normal.dot(p.cast<double>()) - rig.plane_offset_m));
    std::sort(plane.begin(), plane.end());
    std::printf("phase shift: %zu points; distance to the plane: median %.3f mm, 99 %% %.3f mm\n",
                plane.size(), plane[plane.size() / 2] * 1e3, plane[plane.size() * 99 / 100] * 1e3);
    EXPECT_LT(plane[plane.size() / 2], 0.1e-3);
    EXPECT_LT(plane[plane.size() * 99 / 100], 0.5e-3);
}

}  // namespace
}  // namespace anascan::drivers::sl
