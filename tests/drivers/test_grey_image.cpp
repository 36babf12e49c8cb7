// The grey image reader and writer (libjpeg-turbo, libpng) against OpenCV's imgcodecs,
// which they replace in the programs: the same pixels for what both read.
#include <gtest/gtest.h>

#include <fstream>
#include <iterator>
#include <opencv2/core.hpp>
#include <opencv2/imgcodecs.hpp>
#include <vector>

#include "anascan/drivers/grey_image.hpp"
#include "anascan/drivers/structured_light/image_files.hpp"
#include "temp_folder.hpp"

namespace anascan::drivers {
namespace {

/// A smooth pattern with texture: what a camera sees of a projected stripe.
cv::Mat pattern(int rows, int cols, int type) {
    cv::Mat m(rows, cols, type);
    cv::randu(m, cv::Scalar::all(0), cv::Scalar::all(type == CV_16UC1 ? 65535 : 255));
    return m;
}

std::vector<std::uint8_t> bytes_of(const std::filesystem::path& file) {
    std::ifstream in(file, std::ios::binary);
    return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

double max_difference(const cv::Mat& a, const cv::Mat& b) {
    if (a.size() != b.size() || a.type() != b.type()) return 1e9;
    return cv::norm(a, b, cv::NORM_INF);
}

class GreyImage : public ::testing::Test {
protected:
    test::TempFolder folder_;
    std::filesystem::path file(const std::string& name) const { return folder_.path() / name; }

    /// Written by OpenCV, read by both; the two must agree exactly.
    void expect_as_opencv_reads(const std::string& name, const cv::Mat& written) {
        ASSERT_TRUE(cv::imwrite(file(name).string(), written));
        cv::Mat ours;
        const auto read = read_grey_image(file(name), ours);
        ASSERT_TRUE(read) << read.error().message;
        const cv::Mat theirs = cv::imread(file(name).string(), cv::IMREAD_GRAYSCALE);
        EXPECT_EQ(ours.type(), CV_8UC1);
        EXPECT_EQ(max_difference(ours, theirs), 0.0) << name;
    }
};

TEST_F(GreyImage, JpegReadsAsOpenCvReadsIt) {
    expect_as_opencv_reads("grey.jpg", pattern(120, 161, CV_8UC1));
    expect_as_opencv_reads("colour.jpg", pattern(75, 64, CV_8UC3));
}

TEST_F(GreyImage, GreyAndSixteenBitPngReadAsOpenCvReadsThem) {
    expect_as_opencv_reads("grey.png", pattern(33, 47, CV_8UC1));
    expect_as_opencv_reads("wide.png", pattern(21, 13, CV_16UC1));
}

TEST_F(GreyImage, AColourPngOfGreysKeepsItsGreyLevels) {
    cv::Mat grey = pattern(9, 11, CV_8UC1), colour;
    cv::merge(std::vector<cv::Mat>{grey, grey, grey}, colour);
    ASSERT_TRUE(cv::imwrite(file("colour.png").string(), colour));
    cv::Mat ours;
    ASSERT_TRUE(read_grey_image(file("colour.png"), ours));
    EXPECT_EQ(max_difference(ours, grey), 0.0);
}

TEST_F(GreyImage, AnImageOfTheRightSizeIsDecodedInPlace) {
    ASSERT_TRUE(cv::imwrite(file("a.png").string(), pattern(40, 30, CV_8UC1)));
    cv::Mat block(80, 30, CV_8UC1, cv::Scalar(0));
    cv::Mat lower = block.rowRange(40, 80);
    ASSERT_TRUE(read_grey_image(file("a.png"), lower));
    EXPECT_EQ(lower.data, block.data + 40 * block.step);
    EXPECT_EQ(max_difference(block.rowRange(40, 80), cv::imread(file("a.png").string(), 0)), 0.0);
    cv::Mat small(10, 10, CV_8UC1);
    ASSERT_TRUE(read_grey_image(file("a.png"), small));
    EXPECT_EQ(small.size(), cv::Size(30, 40));  // another size: a buffer of its own
}

TEST_F(GreyImage, WrittenPngReadsBackExactly) {
    const cv::Mat written = pattern(57, 83, CV_8UC1);
    ASSERT_TRUE(write_grey_png(file("w.png"), written));
    cv::Mat ours;
    ASSERT_TRUE(read_grey_image(file("w.png"), ours));
    EXPECT_EQ(max_difference(ours, written), 0.0);
    EXPECT_EQ(max_difference(cv::imread(file("w.png").string(), cv::IMREAD_UNCHANGED), written),
              0.0);
    const auto refused = write_grey_png(file("c.png"), pattern(4, 4, CV_8UC3));
    ASSERT_FALSE(refused);
    EXPECT_NE(refused.error().message.find("c.png"), std::string::npos);
    const auto unwritable = write_grey_png(file("no/such/folder/w.png"), written);
    ASSERT_FALSE(unwritable);
    EXPECT_NE(unwritable.error().message.find("w.png: cannot write the image"), std::string::npos);
}

TEST_F(GreyImage, TruncatedAndForeignFilesAreRefusedNamingTheFile) {
    ASSERT_TRUE(cv::imwrite(file("whole.jpg").string(), pattern(64, 64, CV_8UC1)));
    std::vector<std::uint8_t> jpeg = bytes_of(file("whole.jpg"));
    cv::Mat image;
    const std::vector<std::uint8_t> half(jpeg.begin(),
                                         jpeg.begin() + std::ptrdiff_t(jpeg.size() / 2));
    auto r = decode_grey_image(half, "half.jpg", image);
    ASSERT_FALSE(r);
    EXPECT_EQ(r.error().code, ErrorCode::kFormat);
    EXPECT_EQ(r.error().message.rfind("half.jpg: not a readable image (JPEG: ", 0), 0u)
        << r.error().message;
    ASSERT_TRUE(cv::imwrite(file("whole.png").string(), pattern(64, 64, CV_8UC1)));
    std::vector<std::uint8_t> png = bytes_of(file("whole.png"));
    png.resize(png.size() / 2);
    r = decode_grey_image(png, "half.png", image);
    ASSERT_FALSE(r);
    EXPECT_EQ(r.error().message.rfind("half.png: not a readable image (PNG: ", 0), 0u)
        << r.error().message;
    const std::vector<std::uint8_t> bmp = {'B', 'M', 0, 0, 0, 0};
    r = decode_grey_image(bmp, "x.bmp", image);
    ASSERT_FALSE(r);
    EXPECT_EQ(r.error().message, "x.bmp: not a readable image (neither JPEG nor PNG)");
    r = decode_grey_image({}, "empty.jpg", image);
    ASSERT_FALSE(r);
    cv::Mat missing;
    r = read_grey_image(file("missing.jpg"), missing);
    ASSERT_FALSE(r);
    EXPECT_EQ(r.error().code, ErrorCode::kIo);
    EXPECT_NE(r.error().message.find("missing.jpg: no such file"), std::string::npos);
}

// A header that announces 65500 x 65500 pixels (4 GB) is refused before any allocation.
TEST_F(GreyImage, AHugeAnnouncedSizeIsRefusedBeforeAllocating) {
    ASSERT_TRUE(cv::imwrite(file("small.jpg").string(), pattern(8, 8, CV_8UC1)));
    std::vector<std::uint8_t> jpeg = bytes_of(file("small.jpg"));
    std::size_t sof = 0;
    for (std::size_t k = 2; k + 9 < jpeg.size(); ++k) {
        if (jpeg[k] == 0xFF && jpeg[k + 1] == 0xC0) {
            sof = k;
            break;
        }
    }
    ASSERT_GT(sof, 0u);
    for (std::size_t at : {sof + 5, sof + 7}) {  // height, then width, big-endian
        jpeg[at] = 0xFF;
        jpeg[at + 1] = 0xDC;
    }
    cv::Mat image;
    const auto r = decode_grey_image(jpeg, "huge.jpg", image);
    ASSERT_FALSE(r);
    EXPECT_NE(r.error().message.find("65500 x 65500 pixels is too large"), std::string::npos)
        << r.error().message;
    EXPECT_TRUE(image.empty());
}

TEST_F(GreyImage, ASequenceLoadsIntoOneBlockAsOpenCvReadsIt) {
    std::vector<std::filesystem::path> files;
    for (int i = 0; i < 5; ++i) {
        files.push_back(file("im" + std::to_string(i) + ".jpg"));
        ASSERT_TRUE(cv::imwrite(files.back().string(), pattern(48, 64, CV_8UC1)));
    }
    auto images = sl::load_grey_images(files);
    ASSERT_TRUE(images) << images.error().message;
    for (std::size_t i = 0; i < files.size(); ++i) {
        EXPECT_EQ(max_difference((*images)[i], cv::imread(files[i].string(), 0)), 0.0) << i;
        EXPECT_EQ((*images)[i].data, (*images)[0].data + i * 48 * 64) << i;
    }
}

}  // namespace
}  // namespace anascan::drivers
