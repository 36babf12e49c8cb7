// A function run in a child process: its result comes back, and a child that never
// returns, crashes, exits early or cannot be started ends in an error naming the subject,
// with no descriptor, thread or child left behind.
#include <gtest/gtest.h>
#include <signal.h>
#include <sys/resource.h>
#include <sys/time.h>
#include <unistd.h>

#include <chrono>
#include <cstdlib>
#include <future>
#include <stdexcept>
#include <thread>
#include <vector>

#include "isolated_call.hpp"
#include "process_resources.hpp"

namespace anascan::drivers {
namespace {

using namespace std::chrono_literals;
using test::has_child;
using test::open_descriptors;

const IsolatedCallConfig kConfig{
    .subject = "input.yml", .worker = "the test worker", .time_limit = 2000ms};

class IsolatedCall : public ::testing::Test {
protected:
    std::size_t descriptors_before_ = open_descriptors();
    std::size_t threads_before_ = test::threads();
    void TearDown() override {
        EXPECT_EQ(open_descriptors(), descriptors_before_);
        EXPECT_EQ(test::threads_settled_to(threads_before_), threads_before_);
        EXPECT_FALSE(has_child());
    }
};

bool says(const Error& error, const std::string& part) {
    return error.message.find(part) != std::string::npos;
}

TEST_F(IsolatedCall, ReturnsTheBytesOfTheWork) {
    const auto small = call_isolated(kConfig, [] { return std::string("calibration"); });
    ASSERT_TRUE(small) << small.error().message;
    EXPECT_EQ(*small, "calibration");
    const auto empty = call_isolated(kConfig, [] { return std::string(); });
    ASSERT_TRUE(empty) << empty.error().message;
    EXPECT_TRUE(empty->empty());
    // Larger than a pipe's buffer: the child blocks until the parent reads.
    std::string large(1 << 20, '\0');
    for (std::size_t i = 0; i < large.size(); ++i) large[i] = static_cast<char>(i * 7919 % 251);
    const auto copy = call_isolated(kConfig, [&] { return large; });
    ASSERT_TRUE(copy) << copy.error().message;
    EXPECT_EQ(*copy, large);
}

TEST_F(IsolatedCall, AWorkThatNeverReturnsIsKilledAtTheTimeLimit) {
    const auto start = std::chrono::steady_clock::now();
    const auto hung = call_isolated(
        {.subject = "input.yml", .worker = "the test worker", .time_limit = 300ms}, [] {
            for (;;) ::pause();
            return std::string();
        });
    const auto took = std::chrono::steady_clock::now() - start;
    ASSERT_FALSE(hung);
    EXPECT_EQ(hung.error().code, ErrorCode::kTimeout);
    EXPECT_EQ(hung.error().message,
              "input.yml: the test worker did not finish within 0.3 s (malformed file?)");
    EXPECT_GE(took, 300ms);
    EXPECT_LT(took, 1300ms);
}

TEST_F(IsolatedCall, ACrashIsReportedWithItsSignal) {
    const auto segv = call_isolated(kConfig, [] {
        ::raise(SIGSEGV);
        return std::string("unreached");
    });
    ASSERT_FALSE(segv);
    EXPECT_EQ(segv.error().code, ErrorCode::kFormat);
    EXPECT_EQ(segv.error().message,
              "input.yml: the test worker crashed (signal SIGSEGV) on this file");
    const auto abort = call_isolated(kConfig, []() -> std::string { std::abort(); });
    ASSERT_FALSE(abort);
    EXPECT_TRUE(says(abort.error(), "crashed (signal SIGABRT)")) << abort.error().message;
}

TEST_F(IsolatedCall, AnEarlyExitOrAThrowIsReportedWithTheExitStatus) {
    const auto exited = call_isolated(kConfig, []() -> std::string { ::_exit(3); });
    ASSERT_FALSE(exited);
    EXPECT_EQ(exited.error().message, "input.yml: the test worker exited with status 3");
    const auto threw =
        call_isolated(kConfig, []() -> std::string { throw std::runtime_error("boom"); });
    ASSERT_FALSE(threw);
    EXPECT_TRUE(says(threw.error(), "the test worker exited with status")) << threw.error().message;
}

TEST_F(IsolatedCall, AChildThatEndsWithoutItsWholeResultIsReportedAsTruncated) {
    const auto silent = call_isolated(kConfig, []() -> std::string { ::_exit(0); });
    ASSERT_FALSE(silent);
    EXPECT_EQ(silent.error().code, ErrorCode::kFormat);
    EXPECT_EQ(silent.error().message,
              "input.yml: the test worker sent a truncated result (0 bytes, no header)");
}

TEST(IsolatedCallFrame, OnlyACompleteFrameHasAPayload) {
    const std::string frame = frame_message("payload");
    ASSERT_EQ(frame.size(), 8u + 7u);
    EXPECT_EQ(unframe_message(frame), "payload");
    for (std::size_t n = 0; n < frame.size(); ++n)
        EXPECT_FALSE(unframe_message(std::string_view(frame).substr(0, n))) << n;
    EXPECT_FALSE(unframe_message(frame + "x"));
    EXPECT_EQ(unframe_message(frame_message("")), "");
}

extern "C" void count_alarm(int) {}

// The parent's poll is interrupted every 5 ms by a signal without SA_RESTART.
TEST_F(IsolatedCall, SignalsInterruptingTheWaitAreRetried) {
    struct sigaction action {};
    action.sa_handler = count_alarm;
    struct sigaction previous {};
    ASSERT_EQ(::sigaction(SIGALRM, &action, &previous), 0);
    const itimerval every_5_ms{.it_interval = {0, 5000}, .it_value = {0, 5000}};
    ASSERT_EQ(::setitimer(ITIMER_REAL, &every_5_ms, nullptr), 0);
    const auto slow = call_isolated(kConfig, [] {
        std::this_thread::sleep_for(200ms);
        return std::string("done");
    });
    const itimerval off{};
    ::setitimer(ITIMER_REAL, &off, nullptr);
    ::sigaction(SIGALRM, &previous, nullptr);
    ASSERT_TRUE(slow) << slow.error().message;
    EXPECT_EQ(*slow, "done");
}

TEST_F(IsolatedCall, CallsFromSeveralThreadsGetTheirOwnResults) {
    std::vector<std::future<Expected<std::string>>> calls;
    for (int i = 0; i < 6; ++i) {
        calls.push_back(std::async(std::launch::async, [i] {
            return call_isolated(kConfig, [i] { return std::to_string(i); });
        }));
    }
    for (int i = 0; i < 6; ++i) {
        const auto result = calls[i].get();
        ASSERT_TRUE(result) << result.error().message;
        EXPECT_EQ(*result, std::to_string(i));
    }
}

/// Exits 0 when a call started with no room for a pipe fails with kIo naming the pipe.
[[noreturn]] void call_without_room_for_a_pipe() {
    const rlimit three{3, 3};  // stdin, stdout, stderr
    ::setrlimit(RLIMIT_NOFILE, &three);
    const auto r = call_isolated(kConfig, [] { return std::string("x"); });
    std::_Exit(!r && r.error().code == ErrorCode::kIo &&
                       r.error().message ==
                           "input.yml: the test worker could not be started "
                           "(pipe: Too many open files)"
                   ? 0
                   : 1);
}

/// Exits 0 when a call started with no room for a process fails with kIo naming fork.
[[noreturn]] void call_without_room_for_a_process() {
    // The limit on processes does not bind root: run as another user first.
    if (::geteuid() == 0 && ::setuid(65534) != 0) std::_Exit(2);
    const rlimit none{0, 0};
    ::setrlimit(RLIMIT_NPROC, &none);
    const auto r = call_isolated(kConfig, [] { return std::string("x"); });
    std::_Exit(!r && r.error().code == ErrorCode::kIo &&
                       says(r.error(), "input.yml: the test worker could not be started (fork: ")
                   ? 0
                   : 1);
}

// Each in a death test's own process, so that the lowered limits end with it.
TEST(IsolatedCallStart, NoPipeOrNoProcessIsAnIoErrorNotACrash) {
    EXPECT_EXIT(call_without_room_for_a_pipe(), ::testing::ExitedWithCode(0), "");
    EXPECT_EXIT(call_without_room_for_a_process(), ::testing::ExitedWithCode(0), "");
}

}  // namespace
}  // namespace anascan::drivers
