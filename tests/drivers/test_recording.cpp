// Recording as a decorator, playback as a camera, and what a crash can leave behind.
#include <gtest/gtest.h>

#include <fstream>

#include "anascan/drivers/device_registry.hpp"
#include "anascan/drivers/recording.hpp"
#include "mock_pixel.hpp"
#include "scripted_camera.hpp"
#include "temp_folder.hpp"

namespace anascan::drivers {
namespace {

using std::chrono::milliseconds;

void record_frames(const std::filesystem::path& folder, int frames) {
    auto recorder =
        record_camera(test::make_scripted_camera(), {.folder = folder, .fsync_every_frames = 2});
    ASSERT_TRUE(recorder) << recorder.error().message;
    Camera& camera = **recorder;
    ASSERT_TRUE(camera.configure({.exposure_us = 250.0}));
    ASSERT_TRUE(camera.start_stream());
    for (int i = 0; i < frames; ++i) ASSERT_TRUE(camera.next_frame(milliseconds(100)));
    camera.stop_stream();
    camera.close();
}

std::vector<Frame> play_all(const std::filesystem::path& folder, Error* end = nullptr) {
    auto camera = open_playback({.folder = folder});
    EXPECT_TRUE(camera) << camera.error().message;
    if (!camera) return {};
    EXPECT_TRUE((*camera)->start_stream());
    std::vector<Frame> frames;
    for (;;) {
        auto f = (*camera)->next_frame(milliseconds(10));
        if (!f) {
            if (end) *end = f.error();
            return frames;
        }
        frames.push_back(std::move(*f));
    }
}

TEST(Recording, PlaybackIsTheSameCameraWithTheSameFrames) {
    test::TempFolder tmp;
    record_frames(tmp.path() / "rec", 5);
    auto camera = open_playback({.folder = tmp.path() / "rec"});
    ASSERT_TRUE(camera) << camera.error().message;
    EXPECT_EQ((*camera)->info().uri, "playback:" + (tmp.path() / "rec").string());
    EXPECT_EQ((*camera)->info().model, "scripted camera (playback)");
    EXPECT_DOUBLE_EQ((*camera)->settings().exposure_us.value_or(0), 250.0);
    EXPECT_NE((*camera)->calibration_json().find("fx_px"), std::string::npos);
    Error end;
    const std::vector<Frame> frames = play_all(tmp.path() / "rec", &end);
    ASSERT_EQ(frames.size(), 5u);
    for (std::uint64_t i = 0; i < frames.size(); ++i) {
        EXPECT_EQ(frames[i].sequence, i);
        EXPECT_EQ(frames[i].z16_at(3, 4), test::mock_pixel(3, 4, i));
    }
    EXPECT_EQ(end.code, ErrorCode::kEmpty);
    EXPECT_NE(end.message.find("end of recording"), std::string::npos);
}

TEST(Recording, ACutLastRecordIsIgnored) {
    test::TempFolder tmp;
    record_frames(tmp.path(), 4);
    const auto file = tmp.path() / "frames.bin";
    std::filesystem::resize_file(file, std::filesystem::file_size(file) - 10);  // crash mid-write
    Error end;
    EXPECT_EQ(play_all(tmp.path(), &end).size(), 3u);
    EXPECT_EQ(end.code, ErrorCode::kEmpty);
    EXPECT_NE(end.message.find("cut short or corrupt"), std::string::npos) << end.message;
}

TEST(Recording, ACorruptPayloadStopsPlaybackThere) {
    test::TempFolder tmp;
    record_frames(tmp.path(), 4);
    const auto file = tmp.path() / "frames.bin";
    const std::size_t record = std::filesystem::file_size(file) / 4;
    std::fstream f(file, std::ios::in | std::ios::out | std::ios::binary);
    f.seekp(static_cast<std::streamoff>(record + record - 3));  // inside frame 1's payload
    f.put('\x7f');
    f.close();
    Error end;
    EXPECT_EQ(play_all(tmp.path(), &end).size(), 1u);
    EXPECT_NE(end.message.find("frame 1"), std::string::npos) << end.message;
}

TEST(Recording, RefusesToOverwriteARecording) {
    test::TempFolder tmp;
    record_frames(tmp.path(), 1);
    auto again = record_camera(test::make_scripted_camera(), {.folder = tmp.path()});
    ASSERT_FALSE(again);
    EXPECT_EQ(again.error().code, ErrorCode::kInvalidArgument);
}

TEST(Recording, PlaybackOffersOnlyTheRecordedStream) {
    test::TempFolder tmp;
    record_frames(tmp.path(), 1);
    auto camera = open_playback({.folder = tmp.path()});
    ASSERT_TRUE(camera);
    EXPECT_TRUE((*camera)->configure({.profile = StreamProfile{16, 12, PixelFormat::kZ16, 30.0}}));
    auto other = (*camera)->configure({.profile = StreamProfile{32, 24, PixelFormat::kZ16}});
    ASSERT_FALSE(other);
    EXPECT_EQ(other.error().code, ErrorCode::kInvalidArgument);
}

TEST(Recording, LoopingPlaybackStartsAgain) {
    test::TempFolder tmp;
    record_frames(tmp.path(), 2);
    auto camera = open_playback({.folder = tmp.path(), .loop = true});
    ASSERT_TRUE(camera);
    ASSERT_TRUE((*camera)->start_stream());
    std::vector<std::uint64_t> seq;
    for (int i = 0; i < 5; ++i) seq.push_back((*camera)->next_frame(milliseconds(1))->sequence);
    EXPECT_EQ(seq, (std::vector<std::uint64_t>{0, 1, 0, 1, 0}));
}

TEST(Recording, BadFoldersAreNamed) {
    test::TempFolder tmp;
    auto missing = make_hardware_registry().open("playback:" + (tmp.path() / "none").string());
    ASSERT_FALSE(missing);
    EXPECT_EQ(missing.error().code, ErrorCode::kIo);
    EXPECT_NE(missing.error().message.find("none/device.json"), std::string::npos);
    std::ofstream(tmp.path() / "device.json") << "{\"format\":\"something else\"}";
    auto bad = open_playback({.folder = tmp.path()});
    ASSERT_FALSE(bad);
    EXPECT_EQ(bad.error().code, ErrorCode::kFormat);
}

}  // namespace
}  // namespace anascan::drivers
