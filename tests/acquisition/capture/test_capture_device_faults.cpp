// Device faults during a capture session: a scanner that delivers garbage (no valid point)
// or the same scan again (frozen), and a scanner unplugged and plugged in again many
// times. Each gives a clear message, nothing is saved from the bad captures, the session
// goes on, and no file descriptor or thread is left behind.
#include <filesystem>

#include "capture_session_fixture.hpp"

namespace anascan::acquisition {
namespace {

std::size_t entries_in(const fs::path& dir) {
    std::size_t n = 0;
    for ([[maybe_unused]] const auto& e : fs::directory_iterator(dir)) ++n;
    return n;
}
std::size_t open_descriptors() { return entries_in("/proc/self/fd"); }
std::size_t threads() { return entries_in("/proc/self/task"); }

/// Every device it opens shares `faults`: the fault stays until the test clears it.
ScannerOpener faulty_tof_opener(std::shared_ptr<sim::SimDeviceFaults> faults, int* opened) {
    return [faults, opened]() -> Expected<std::unique_ptr<drivers::Scanner>> {
        ++*opened;
        return std::unique_ptr<drivers::Scanner>(
            sim::SimTofScanner::open(sim::test::small_tof_config(faults)));
    };
}

bool says(const Error& error, const std::string& part) {
    return error.message.find(part) != std::string::npos;
}

TEST_F(CaptureSessionTest, GarbageAndFrozenScansAreRefusedWithAMessageAndTheSessionGoesOn) {
    auto faults = std::make_shared<sim::SimDeviceFaults>();
    int opened = 0;
    auto session = start({.register_live = false, .coverage_live = false});
    ASSERT_TRUE(session->attach_scanner("sim:tof/small-block", faulty_tof_opener(faults, &opened)));
    ASSERT_TRUE(session->capture({}).get());

    faults->garbage_scans = 1;
    auto garbage = session->capture({}).get();
    ASSERT_FALSE(garbage);
    EXPECT_TRUE(says(garbage.error(), "sim:tof/small-block")) << garbage.error().message;
    EXPECT_TRUE(says(garbage.error(), "no valid point")) << garbage.error().message;

    ASSERT_TRUE(session->capture({}).get());
    faults->frozen = true;
    auto frozen = session->capture({}).get();
    ASSERT_FALSE(frozen);
    EXPECT_TRUE(says(frozen.error(), "frozen")) << frozen.error().message;
    faults->frozen = false;

    auto back = session->capture({}).get();
    ASSERT_TRUE(back) << back.error().message;
    EXPECT_EQ(*back, 3);  // the refused captures used no sequence number
    session->wait_until_idle();
    EXPECT_EQ(count(SessionEventKind::kDeviceError), 2u);
    EXPECT_EQ(opened, 1) << "a refused scan is not a lost device";
    auto scans = session->store().scans();
    ASSERT_TRUE(scans);
    EXPECT_EQ(scans->size(), 3u);
}

TEST_F(CaptureSessionTest, RepeatedUnplugsLeakNoDescriptorsOrThreads) {
    auto faults = std::make_shared<sim::SimDeviceFaults>();
    int opened = 0;
    auto session = start({.register_live = false, .coverage_live = false});
    ASSERT_TRUE(session->attach_scanner("sim:tof/small-block", faulty_tof_opener(faults, &opened)));
    ASSERT_TRUE(session->capture({}).get());  // the threads and the database are up
    session->wait_until_idle();
    const std::size_t descriptors_before = open_descriptors(), threads_before = threads();

    constexpr int kUnplugs = 10;
    for (int i = 0; i < kUnplugs; ++i) {
        faults->unplug_after_captures = 0;
        auto lost = session->capture({}).get();
        ASSERT_FALSE(lost);
        EXPECT_EQ(lost.error().code, ErrorCode::kDisconnected) << lost.error().message;
        faults->unplug_after_captures = -1;  // plugged in again
        auto back = session->capture({}).get();
        ASSERT_TRUE(back) << back.error().message;
    }
    session->wait_until_idle();
    EXPECT_EQ(opened, 1 + kUnplugs);
    EXPECT_EQ(count(SessionEventKind::kDeviceError), std::size_t(kUnplugs));
    EXPECT_EQ(count(SessionEventKind::kDeviceBack), std::size_t(kUnplugs));
    EXPECT_EQ(open_descriptors(), descriptors_before);
    EXPECT_EQ(threads(), threads_before);
    auto scans = session->store().scans();
    ASSERT_TRUE(scans);
    EXPECT_EQ(scans->size(), std::size_t(1 + kUnplugs));
}

}  // namespace
}  // namespace anascan::acquisition
