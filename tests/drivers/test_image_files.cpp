#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <opencv2/imgcodecs.hpp>

#include "anascan/drivers/structured_light/image_files.hpp"

namespace anascan::drivers::sl {
namespace {

TEST(NaturalOrder, NumbersCompareByValue) {
    EXPECT_TRUE(natural_less("im2.jpg", "im10.jpg"));
    EXPECT_FALSE(natural_less("im10.jpg", "im2.jpg"));
    EXPECT_TRUE(natural_less("cam1_im44", "cam2_im1"));
    EXPECT_TRUE(natural_less("a", "b"));
    EXPECT_FALSE(natural_less("im7", "im7"));
    EXPECT_TRUE(natural_less("im01", "im1") != natural_less("im1", "im01"));
}

class ImageFolder : public ::testing::Test {
protected:
    std::filesystem::path dir_ = std::filesystem::temp_directory_path() /
                                 ("anascan_sl_images_" + std::to_string(::getpid()));
    void SetUp() override { std::filesystem::create_directories(dir_); }
    void TearDown() override { std::filesystem::remove_all(dir_); }
};

TEST_F(ImageFolder, GlobSortsNaturallyAndLoads) {
    for (int i : {10, 2, 1}) {
        cv::imwrite((dir_ / ("im" + std::to_string(i) + ".png")).string(),
                    cv::Mat(4, 6, CV_8UC3, cv::Scalar::all(i)));
    }
    auto files = glob_natural((dir_ / "im*.png").string());
    ASSERT_TRUE(files) << files.error().message;
    ASSERT_EQ(files->size(), 3u);
    EXPECT_EQ((*files)[0].filename(), "im1.png");
    EXPECT_EQ((*files)[1].filename(), "im2.png");
    EXPECT_EQ((*files)[2].filename(), "im10.png");
    std::size_t calls = 0;
    auto images = load_grey_images(*files, [&](std::size_t) { ++calls; });
    ASSERT_TRUE(images) << images.error().message;
    EXPECT_EQ(calls, 3u);
    EXPECT_EQ((*images)[2].type(), CV_8UC1);
    EXPECT_EQ((*images)[2].at<std::uint8_t>(0, 0), 10);
}

TEST_F(ImageFolder, ClearErrors) {
    auto files = glob_natural((dir_ / "none*.jpg").string());
    ASSERT_FALSE(files);
    EXPECT_NE(files.error().message.find("no file matches"), std::string::npos);
    std::ofstream(dir_ / "broken.jpg") << "not a jpeg at all";
    const std::vector<std::filesystem::path> list{dir_ / "broken.jpg"};
    auto images = load_grey_images(list);
    ASSERT_FALSE(images);
    EXPECT_NE(images.error().message.find("broken.jpg: not a readable image"), std::string::npos)
        << images.error().message;
    const std::vector<std::filesystem::path> missing{dir_ / "missing.jpg"};
    images = load_grey_images(missing);
    ASSERT_FALSE(images);
    EXPECT_NE(images.error().message.find("missing.jpg: no such file"), std::string::npos);
}

}  // namespace
}  // namespace anascan::drivers::sl
