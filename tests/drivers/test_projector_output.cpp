// The projector window under a virtual X server (xvfb-run): each pattern is on screen,
// read back with glReadPixels, when its callback runs.
#include <gtest/gtest.h>

#include <cstdlib>

#include "anascan/drivers/projector_output.hpp"
#include "x_screen.hpp"

namespace anascan::drivers {
namespace {

/// Gray-code-like stripes: column bit `bit` of each pixel, 0 or 255.
Pattern stripes(int w, int h, int bit) {
    Pattern p{w, h, std::vector<std::uint8_t>(static_cast<std::size_t>(w) * h)};
    for (int r = 0; r < h; ++r)
        for (int c = 0; c < w; ++c)
            p.grey[static_cast<std::size_t>(r) * w + c] = ((c >> bit) & 1) ? 255 : 0;
    p.grey[0] = 128;  // mark the top-left corner: catches a flipped image
    return p;
}

std::size_t differing_pixels(const Pattern& a, const Pattern& b) {
    if (a.grey.size() != b.grey.size()) return std::max(a.grey.size(), b.grey.size());
    std::size_t n = 0;
    for (std::size_t k = 0; k < a.grey.size(); ++k) n += a.grey[k] != b.grey[k];
    return n;
}

class Projector : public ::testing::Test {
protected:
    void SetUp() override {
        if (std::getenv("DISPLAY") == nullptr) GTEST_SKIP() << "no DISPLAY: run under xvfb-run";
        auto projector = ProjectorOutput::open({.monitor_index = 0, .keep_read_back = true});
        if (!projector && projector.error().code == ErrorCode::kUnsupported)
            GTEST_SKIP() << projector.error().message;
        ASSERT_TRUE(projector) << projector.error().message;
        projector_ = std::move(*projector);
    }
    std::unique_ptr<ProjectorOutput> projector_;
};

TEST_F(Projector, FullScreenOnTheChosenMonitor) {
    const std::vector<MonitorInfo> monitors = ProjectorOutput::monitors();
    ASSERT_FALSE(monitors.empty());
    EXPECT_EQ(projector_->width_px(), monitors[0].width_px);
    EXPECT_EQ(projector_->height_px(), monitors[0].height_px);
}

TEST_F(Projector, EachPatternIsOnScreenWhenItsCallbackRuns) {
    const int w = projector_->width_px(), h = projector_->height_px();
    std::vector<Pattern> patterns;
    for (int bit = 7; bit >= 5; --bit) patterns.push_back(stripes(w, h, bit));
    std::vector<std::size_t> shown;
    auto ok = projector_->show_sequence(patterns, [&](std::size_t i) {
        shown.push_back(i);
        EXPECT_EQ(differing_pixels(projector_->read_back(), patterns[i]), 0u)
            << "pattern " << i << " is not in the frame buffer";
        EXPECT_EQ(differing_pixels(test::screen_from_x_server(w, h), patterns[i]), 0u)
            << "pattern " << i << " is not on screen";
        return true;
    });
    ASSERT_TRUE(ok) << ok.error().message;
    EXPECT_EQ(shown, (std::vector<std::size_t>{0, 1, 2}));
}

TEST_F(Projector, StoppingOrAWrongSizeEndsTheSequence) {
    const int w = projector_->width_px(), h = projector_->height_px();
    const std::vector<Pattern> patterns{stripes(w, h, 6), stripes(w, h, 5), stripes(w, h, 4)};
    int calls = 0;
    auto stopped = projector_->show_sequence(patterns, [&](std::size_t i) {
        ++calls;
        return i < 1;
    });
    ASSERT_FALSE(stopped);
    EXPECT_EQ(stopped.error().code, ErrorCode::kCancelled);
    EXPECT_EQ(calls, 2);
    const std::vector<Pattern> small{stripes(w / 2, h, 3)};
    auto wrong = projector_->show_sequence(small, [](std::size_t) { return true; });
    ASSERT_FALSE(wrong);
    EXPECT_EQ(wrong.error().code, ErrorCode::kInvalidArgument);
}

TEST_F(Projector, ClosingTheWindowEndsTheSequenceClearlyAndAReopenWorks) {
    const int w = projector_->width_px(), h = projector_->height_px();
    std::vector<Pattern> patterns;
    for (int bit = 7; bit >= 0; --bit) patterns.push_back(stripes(w, h, bit));
    std::size_t shown = 0;
    auto closed = projector_->show_sequence(patterns, [&](std::size_t i) {
        ++shown;
        if (i == 0) {
            EXPECT_EQ(test::close_windows_titled("anascan projector"), 1);
        }
        return true;
    });
    ASSERT_FALSE(closed) << "the closed window showed every pattern";
    EXPECT_EQ(closed.error().code, ErrorCode::kDisconnected);
    EXPECT_NE(closed.error().message.find("the window was closed"), std::string::npos)
        << closed.error().message;
    EXPECT_LT(shown, patterns.size());
    // The operator opens the projector again: it shows a whole sequence.
    projector_.reset();
    auto again = ProjectorOutput::open({.monitor_index = 0});
    ASSERT_TRUE(again) << again.error().message;
    auto ok = (*again)->show_sequence(patterns, [](std::size_t) { return true; });
    EXPECT_TRUE(ok) << ok.error().message;
}

TEST(ProjectorMonitors, AMissingMonitorIsNamed) {
    if (std::getenv("DISPLAY") == nullptr) GTEST_SKIP() << "no DISPLAY: run under xvfb-run";
    auto projector = ProjectorOutput::open({.monitor_index = 7});
    ASSERT_FALSE(projector);
    EXPECT_NE(projector.error().message.find("monitor 7"), std::string::npos);
}

}  // namespace
}  // namespace anascan::drivers
