#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <filesystem>
#include <fstream>
#include <opencv2/core.hpp>

#include "anascan/drivers/structured_light/stereo_calibration.hpp"

namespace anascan::drivers::sl {
namespace {

class CalibrationFile : public ::testing::Test {
protected:
    std::filesystem::path dir_ =
        std::filesystem::temp_directory_path() / ("anascan_sl_calib_" + std::to_string(::getpid()));
    void SetUp() override { std::filesystem::create_directories(dir_); }
    void TearDown() override { std::filesystem::remove_all(dir_); }

    // OpenCV convention: X_2 = R X_1 + T, T in mm; R turns 20 degrees about y.
    std::filesystem::path write(const std::string& name, bool with_r = true, double r_scale = 1.0) {
        const std::filesystem::path path = dir_ / name;
        cv::FileStorage fs(path.string(), cv::FileStorage::WRITE);
        const cv::Matx33d K1(3000, 0, 960, 0, 3000, 640, 0, 0, 1);
        const cv::Matx33d K2(2900, 0, 950, 0, 2900, 650, 0, 0, 1);
        fs << "cam1_intrinsics" << cv::Mat(K1) << "cam1_distorsion"
           << cv::Mat(cv::Matx<double, 1, 5>(0.1, -0.2, 0, 0, 0.3)) << "cam1_size"
           << std::vector<int>{1920, 1280};
        fs << "cam2_intrinsics" << cv::Mat(K2) << "cam2_distorsion"
           << cv::Mat(cv::Matx<double, 1, 5>(0, 0, 0, 0, 0)) << "cam2_size"
           << std::vector<int>{1920, 1280};
        const Eigen::Matrix3d R =
            Eigen::AngleAxisd(0.35, Eigen::Vector3d::UnitY()).toRotationMatrix();
        cv::Mat Rm(3, 3, CV_64F);
        for (int r = 0; r < 3; ++r)
            for (int c = 0; c < 3; ++c) Rm.at<double>(r, c) = R(r, c) * r_scale;
        if (with_r) fs << "R" << Rm;
        fs << "T" << cv::Mat(cv::Vec3d(-1300.0, 50.0, 400.0));
        return path;
    }
};

TEST_F(CalibrationFile, OpenCvConvention) {
    auto calib = load_stereo_calibration(write("c.yml"), {});
    ASSERT_TRUE(calib) << calib.error().message;
    EXPECT_DOUBLE_EQ(calib->cam1.K(0, 0), 3000.0);
    EXPECT_EQ(calib->cam1.distortion.size(), 5u);
    EXPECT_DOUBLE_EQ(calib->cam1.distortion[4], 0.3);
    EXPECT_EQ(calib->cam2.width_px, 1920);
    // X_2 = R X_1 + T: cam1's origin lies at T (metres) in cam2's frame.
    const Pose T_cam2_cam1 = calib->T_cam1_cam2.inverse();
    EXPECT_TRUE(T_cam2_cam1.translation().isApprox(Eigen::Vector3d(-1.3, 0.05, 0.4), 1e-12));
}

TEST_F(CalibrationFile, SwapExchangesCamerasAndDirection) {
    auto calib = load_stereo_calibration(write("c.yml"), {.swap_cameras = true});
    ASSERT_TRUE(calib) << calib.error().message;
    EXPECT_DOUBLE_EQ(calib->cam1.K(0, 0), 2900.0);  // The file's cam2.
    EXPECT_DOUBLE_EQ(calib->cam2.K(0, 0), 3000.0);
    EXPECT_TRUE(calib->T_cam1_cam2.translation().isApprox(Eigen::Vector3d(-1.3, 0.05, 0.4), 1e-12));
}

TEST_F(CalibrationFile, UnitMetres) {
    auto calib = load_stereo_calibration(write("c.yml"), {.file_unit_m = 1.0});
    ASSERT_TRUE(calib);
    EXPECT_NEAR(calib->T_cam1_cam2.inverse().translation().x(), -1300.0, 1e-9);
}

TEST_F(CalibrationFile, ErrorsNameFileAndKey) {
    auto r = load_stereo_calibration(write("no_r.yml", false), {});
    ASSERT_FALSE(r);
    EXPECT_NE(r.error().message.find("no_r.yml: missing key 'R'"), std::string::npos)
        << r.error().message;
    r = load_stereo_calibration(write("scaled.yml", true, 2.0), {});
    ASSERT_FALSE(r);
    EXPECT_NE(r.error().message.find("'R' is not a rotation"), std::string::npos);
    r = load_stereo_calibration(dir_ / "absent.yml", {});
    ASSERT_FALSE(r);
    EXPECT_EQ(r.error().code, ErrorCode::kIo);
    std::ofstream(dir_ / "garbage.yml") << "%YAML:1.0\ncam1_intrinsics: [1, 2\n";
    r = load_stereo_calibration(dir_ / "garbage.yml", {});
    ASSERT_FALSE(r);
    EXPECT_EQ(r.error().code, ErrorCode::kFormat);
    EXPECT_NE(r.error().message.find("garbage.yml"), std::string::npos);
}

// OpenCV 4.6's YAML parser loops for ever on text after a document start followed by a
// marker-like line (found by fuzz_calibration); without the check this test never returns.
TEST_F(CalibrationFile, TextAfterTheDocumentStartIsRefusedBeforeTheParserCanHang) {
    const std::filesystem::path path = dir_ / "document_start.yml";
    for (const char* start_line : {"---%YAML:1.0", "----YAML:1.0", "--- YAML:2", "---x:y"}) {
        std::ofstream(path) << "%YAML:1.0\n" << start_line << "\n--%-\ncam\n";
        const auto refused = load_stereo_calibration(path, {});
        ASSERT_FALSE(refused) << start_line;
        EXPECT_NE(refused.error().message.find("line 2: text after the document start"),
                  std::string::npos)
            << refused.error().message;
    }
    const auto calibration = load_stereo_calibration(path, {});
    ASSERT_FALSE(calibration);
    EXPECT_EQ(calibration.error().code, ErrorCode::kFormat);
    EXPECT_NE(calibration.error().message.find(path.string() + ": line 2:"), std::string::npos)
        << calibration.error().message;
    const auto layout = load_pattern_layout(path);
    ASSERT_FALSE(layout);
    EXPECT_NE(layout.error().message.find(path.string()), std::string::npos);
}

// OpenCV 4.6's XML parser reads a null pointer on a NUL byte in the header (fuzz_calibration).
TEST_F(CalibrationFile, ANulByteIsRefusedBeforeTheParserCanCrash) {
    const std::filesystem::path path = dir_ / "nul.xml";
    const char bytes[] = "<?xml version=\0\0\"1.0\"?>\n<opencv_storage>\n</opencv_storage>\n";
    std::ofstream(path, std::ios::binary).write(bytes, sizeof(bytes) - 1);
    const auto refused = load_stereo_calibration(path, {});
    ASSERT_FALSE(refused);
    EXPECT_EQ(refused.error().code, ErrorCode::kFormat);
    EXPECT_NE(refused.error().message.find(path.string() + ": byte 14: a NUL byte"),
              std::string::npos)
        << refused.error().message;
}

}  // namespace
}  // namespace anascan::drivers::sl
