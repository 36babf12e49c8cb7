// `anascan sl decode` run as a user runs it: a rendered capture on disk, and broken ones.
#include <gtest/gtest.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <opencv2/core.hpp>
#include <opencv2/imgcodecs.hpp>

#include "anascan/drivers/structured_light/gray_code.hpp"
#include "anascan/processing/io/ply.hpp"
#include "cli_runner.hpp"
#include "sl_synthetic.hpp"

namespace anascan::test {
namespace {

namespace fs = std::filesystem;
namespace sl = drivers::sl;
using testing_util::CliRun;
using testing_util::run_cli;

/// Writes the calibration like OpenCV's stereoCalibrate would: X_2 = R X_1 + T, mm.
void write_calibration(const fs::path& path, const sl::StereoCalibration& c) {
    cv::FileStorage out(path.string(), cv::FileStorage::WRITE);
    const auto write_camera = [&](const std::string& name, const sl::CameraIntrinsics& cam) {
        cv::Mat K(3, 3, CV_64F);
        for (int r = 0; r < 3; ++r)
            for (int k = 0; k < 3; ++k) K.at<double>(r, k) = cam.K(r, k);
        out << name + "_intrinsics" << K << name + "_distorsion" << cv::Mat::zeros(1, 5, CV_64F)
            << name + "_size" << std::vector<int>{cam.width_px, cam.height_px};
    };
    write_camera("cam1", c.cam1);
    write_camera("cam2", c.cam2);
    const Pose T_2_1 = c.T_cam1_cam2.inverse();
    cv::Mat R(3, 3, CV_64F), T(3, 1, CV_64F);
    for (int r = 0; r < 3; ++r) {
        for (int k = 0; k < 3; ++k) R.at<double>(r, k) = T_2_1.linear()(r, k);
        T.at<double>(r) = T_2_1.translation()(r) * 1e3;
    }
    out << "R" << R << "T" << T;
}

class SlDecodeCli : public ::testing::Test {
protected:
    static void SetUpTestSuite() {
        dir_ = fs::path(::testing::TempDir()) / ("cli-sl-" + std::to_string(::getpid()));
        fs::remove_all(dir_);
        fs::create_directories(dir_ / "capture");
        const SyntheticRig rig = make_rig();
        const auto patterns = sl::make_gray_code_patterns(rig.projector);
        for (int cam : {1, 2}) {
            const auto images = render(rig, cam, patterns, {.supersample = 2, .bilinear = true});
            for (std::size_t i = 0; i < images.size(); ++i) {
                cv::imwrite((dir_ / "capture" /
                             ("cam" + std::to_string(cam) + "_im" + std::to_string(i + 1) + ".png"))
                                .string(),
                            images[i]);
            }
        }
        write_calibration(dir_ / "calibration.yml", rig.calibration);
    }
    static void TearDownTestSuite() { fs::remove_all(dir_); }

    /// The command's arguments on a copy of the capture that `damage` may break first.
    static std::string decode_args(const std::string& extra = "",
                                   const std::function<void(const fs::path&)>& damage = {}) {
        const fs::path work = dir_ / ("run" + std::to_string(++runs_));
        fs::copy(dir_ / "capture", work);
        if (damage) damage(work);
        return "sl decode --calibration " + (dir_ / "calibration.yml").string() +
               " --projector-width 320 --projector-height 200 --cam1 '" +
               (work / "cam1_im*.png").string() + "' --cam2 '" + (work / "cam2_im*.png").string() +
               "' --out " + (work / "cloud.ply").string() + " " + extra;
    }
    static CliRun decode(const std::string& extra = "",
                         const std::function<void(const fs::path&)>& damage = {}) {
        return run_cli(decode_args(extra, damage));
    }

    static inline fs::path dir_;
    static inline int runs_ = 0;
};

TEST_F(SlDecodeCli, WritesACloudWithUnits) {
    const CliRun run = decode();
    ASSERT_EQ(run.exit_code, 0) << run.output;
    EXPECT_NE(run.output.find("points: "), std::string::npos) << run.output;
    EXPECT_NE(run.output.find(" s (load 72 images"), std::string::npos) << run.output;
    EXPECT_NE(run.output.find("median ray gap"), std::string::npos) << run.output;
    auto ply = io::read_ply(dir_ / ("run" + std::to_string(runs_)) / "cloud.ply");
    ASSERT_TRUE(ply) << ply.error().message;
    EXPECT_GT(ply->cloud.size(), 50000u);
}

// Cameras in the wrong order: most matches miss each other by more than the ray-gap limit.
// The result is written but clearly unusable: exit code 3 unless --accept-poor. This small
// rendered rig's swapped rays still meet within a few millimetres (median 7.5 mm), so the
// limit is set to 2 mm, which the right order passes.
TEST_F(SlDecodeCli, CamerasInTheWrongOrderArePoorResult) {
    const CliRun right = decode("--max-ray-gap 2");
    EXPECT_EQ(right.exit_code, 0) << right.output;
    const CliRun run = decode("--swap-cameras --max-ray-gap 2");
    EXPECT_EQ(run.exit_code, 3) << run.output;
    EXPECT_NE(run.output.find("poor result: "), std::string::npos) << run.output;
    EXPECT_NE(run.output.find("--swap-cameras"), std::string::npos) << run.output;
    EXPECT_TRUE(fs::exists(dir_ / ("run" + std::to_string(runs_)) / "cloud.ply"));
    const CliRun accepted =
        run_cli("--accept-poor " + decode_args("--swap-cameras --max-ray-gap 2"));
    EXPECT_EQ(accepted.exit_code, 0) << accepted.output;
    EXPECT_NE(accepted.output.find("poor result: "), std::string::npos) << accepted.output;
}

TEST_F(SlDecodeCli, MissingImages) {
    const CliRun run = decode("", [](const fs::path& w) {
        for (int i = 1; i <= 36; ++i) fs::remove(w / ("cam2_im" + std::to_string(i) + ".png"));
    });
    EXPECT_EQ(run.exit_code, 1);
    EXPECT_NE(run.output.find("cam2_im*.png: no file matches"), std::string::npos) << run.output;
}

TEST_F(SlDecodeCli, WrongCount) {
    const CliRun run = decode("", [](const fs::path& w) { fs::remove(w / "cam1_im7.png"); });
    EXPECT_EQ(run.exit_code, 1);
    EXPECT_NE(run.output.find("matches 35 files, the sequence has 36 images"), std::string::npos)
        << run.output;
}

TEST_F(SlDecodeCli, UnreadableImage) {
    const CliRun run = decode("", [](const fs::path& w) {
        std::ofstream(w / "cam1_im12.png", std::ios::trunc) << "garbage";
    });
    EXPECT_EQ(run.exit_code, 1);
    EXPECT_NE(run.output.find("cam1_im12.png: not a readable image"), std::string::npos)
        << run.output;
}

TEST_F(SlDecodeCli, SizeMismatch) {
    const CliRun run = decode("", [](const fs::path& w) {
        cv::imwrite((w / "cam2_im5.png").string(), cv::Mat(240, 320, CV_8UC1, cv::Scalar(9)));
    });
    EXPECT_EQ(run.exit_code, 1);
    EXPECT_NE(run.output.find("cam2: image 5 is 320x240 px, image 1 is 640x480 px"),
              std::string::npos)
        << run.output;
}

TEST_F(SlDecodeCli, BadCalibration) {
    std::ofstream(dir_ / "bad.yml") << "%YAML:1.0\nR: 3\n";
    const CliRun run = run_cli("sl decode --calibration " + (dir_ / "bad.yml").string() +
                               " --cam1 'x*' --cam2 'y*' --out o.ply");
    EXPECT_EQ(run.exit_code, 1);
    EXPECT_NE(run.output.find("bad.yml: missing key 'cam1_intrinsics'"), std::string::npos)
        << run.output;
}

}  // namespace
}  // namespace anascan::test
