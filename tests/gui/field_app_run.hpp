#pragma once
// Shared by the tests that run anascan-field (and anascan) as processes: run a command line
// and collect its output, compare screenshot pixels with the view's background.
#include <gtest/gtest.h>
#include <sys/wait.h>
#include <unistd.h>

#include <array>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <opencv2/core.hpp>
#include <string>

namespace anascan::test {

struct RunResult {
    int exit_code = -1;
    std::string output;  // stdout, and stderr when merged
};

/// Runs `command` through the shell; `stderr_too`: merge stderr into the output, else drop
/// it (a JSON document on stdout).
inline RunResult run_command(const std::string& command, bool stderr_too = true) {
    const std::string line = command + (stderr_too ? " 2>&1" : " 2>/dev/null");
    RunResult result;
    FILE* pipe = popen(line.c_str(), "r");
    if (pipe == nullptr) return result;
    std::array<char, 4096> buffer{};
    while (std::fgets(buffer.data(), buffer.size(), pipe) != nullptr)
        result.output += buffer.data();
    const int status = pclose(pipe);
    result.exit_code = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
    return result;
}

/// Fraction of pixels in the rectangle that differ from `rgb` by more than 24 in a channel.
inline double fraction_not(const cv::Mat& bgr, cv::Rect rect, cv::Vec3b rgb) {
    int differing = 0;
    for (int y = rect.y; y < rect.y + rect.height; ++y) {
        for (int x = rect.x; x < rect.x + rect.width; ++x) {
            const cv::Vec3b p = bgr.at<cv::Vec3b>(y, x);
            const bool same = std::abs(p[2] - rgb[0]) <= 24 && std::abs(p[1] - rgb[1]) <= 24 &&
                              std::abs(p[0] - rgb[2]) <= 24;
            if (!same) ++differing;
        }
    }
    return static_cast<double>(differing) / rect.area();
}

/// Why a test that needs a display skips without one.
inline constexpr const char* kNoDisplay =
    "no DISPLAY: this test runs under xvfb-run (Debian xvfb, installed by scripts/setup.sh); "
    "reconfigure after installing it";

/// An empty folder for the running test: TMP/PREFIX_PID_TESTNAME.
inline std::filesystem::path fresh_test_dir(const std::string& prefix) {
    const auto dir = std::filesystem::temp_directory_path() /
                     (prefix + std::to_string(::getpid()) + "_" +
                      ::testing::UnitTest::GetInstance()->current_test_info()->name());
    std::filesystem::remove_all(dir);
    std::filesystem::create_directories(dir);
    return dir;
}

inline const cv::Vec3b kClearRgb{41, 46, 56};  // glClearColor(0.16, 0.18, 0.22) of the view

}  // namespace anascan::test
