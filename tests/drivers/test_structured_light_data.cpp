// The real GSoC 2015 statue captures (../shared/data/gsoc2015-statue-graycode-stereo):
// our decoder against OpenCV's own Gray-code path on the same images.
#include <gtest/gtest.h>

#include <cstdio>
#include <filesystem>

#include "anascan/drivers/structured_light/image_files.hpp"
#include "anascan/drivers/structured_light/stereo_decoder.hpp"
#include "sl_reference.hpp"

namespace anascan::drivers::sl {
namespace {

const std::filesystem::path kData =
    std::filesystem::path(ANASCAN_SHARED_DATA_DIR) / "gsoc2015-statue-graycode-stereo";

struct SideFiles {
    std::vector<std::filesystem::path> cam1, cam2;
};

SideFiles side_files(const std::string& side) {
    const std::string dir = (kData / side).string();
    auto cam1 = glob_natural(dir + "/pattern_cam1_im*.jpg");
    auto cam2 = glob_natural(dir + "/pattern_cam2_im*.jpg");
    if (!cam1 || !cam2) return {};
    return {*cam1, *cam2};
}

Expected<StereoDecodeResult> decode_side(const SideFiles& files) {
    auto calibration = load_stereo_calibration(kData / "calibrationParameters.yml",
                                               {.swap_cameras = true, .file_unit_m = 1e-3});
    if (!calibration) return fail(calibration.error());
    auto cam1 = load_grey_images(files.cam1);
    if (!cam1) return fail(cam1.error());
    auto cam2 = load_grey_images(files.cam2);
    if (!cam2) return fail(cam2.error());
    return decode_stereo(*cam1, *cam2, *calibration, {});
}

class StatueData : public ::testing::TestWithParam<const char*> {
protected:
    void SetUp() override {
        if (!std::filesystem::exists(kData / "calibrationParameters.yml"))
            GTEST_SKIP() << "GSoC statue data absent: " << kData;
    }
};

// Dense and no noisier than OpenCV's path (rectify, GrayCodePattern::decode,
// reprojectImageTo3D) on the same side.
TEST_P(StatueData, DenserAndNoNoisierThanOpenCv) {
    const SideFiles files = side_files(GetParam());
    ASSERT_EQ(files.cam1.size(), 44u);
    ASSERT_EQ(files.cam2.size(), 44u);
    auto ours = decode_side(files);
    ASSERT_TRUE(ours) << ours.error().message;
    const auto peer = test::run_opencv_graycode(kData / "calibrationParameters.yml", files.cam1,
                                                files.cam2, 1280, 800);
    ASSERT_TRUE(peer.ok) << peer.error;
    const double our_noise = test::median_local_noise_m(ours->cloud);
    const double peer_noise = test::median_local_noise_m(peer.cloud);
    std::printf(
        "%s: ours %zu points, local noise %.3f mm, median ray gap %.2f mm; "
        "OpenCV %zu points, local noise %.3f mm\n",
        GetParam(), ours->cloud.size(), our_noise * 1e3, ours->median_ray_gap_m * 1e3,
        peer.cloud.size(), peer_noise * 1e3);
    EXPECT_GE(ours->cloud.size(), peer.cloud.size());
    EXPECT_LE(our_noise, peer_noise);
    // Plausible geometry: the statue stands ~2.7 m in front of the cameras (README).
    const Bounds b = local_bounds(ours->cloud);
    EXPECT_GT(b.min.z(), 1.5f);
    EXPECT_LT(b.max.z(), 4.0f);
    // The calibration is approximate (README: ~7 mm gap at 2.7 m), not broken.
    EXPECT_LT(ours->median_ray_gap_m, 0.012);
}

INSTANTIATE_TEST_SUITE_P(Sides, StatueData,
                         ::testing::Values("statue_front_side", "statue_back_side"));

}  // namespace
}  // namespace anascan::drivers::sl
