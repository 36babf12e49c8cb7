#pragma once
// A capture session on a real session store in a temporary folder, with its events
// collected, and a simulated ToF scanner to attach.
#include <gtest/gtest.h>
#include <unistd.h>

#include <algorithm>
#include <filesystem>
#include <memory>
#include <mutex>
#include <vector>

#include "anascan/acquisition/capture/capture_session.hpp"
#include "sim_devices_fixture.hpp"

namespace anascan::acquisition {

namespace fs = std::filesystem;

class CaptureSessionTest : public ::testing::Test {
protected:
    void SetUp() override {
        dir_ = fs::path(::testing::TempDir()) / ("capture-" + std::to_string(::getpid()));
        fs::remove_all(dir_);
    }
    void TearDown() override { fs::remove_all(dir_); }

    std::unique_ptr<CaptureSession> start(CaptureSessionConfig config = {}) {
        auto store = SessionStore::open(dir_, SessionOpenMode::kCreateOrOpen);
        EXPECT_TRUE(store) << store.error().message;
        auto session =
            CaptureSession::start(std::move(*store), config, [this](const SessionEvent& e) {
                std::lock_guard lock(mutex_);
                events_.push_back(e);
            });
        EXPECT_TRUE(session) << session.error().message;
        return std::move(*session);
    }

    std::size_t count(SessionEventKind kind) {
        std::lock_guard lock(mutex_);
        return static_cast<std::size_t>(std::count_if(
            events_.begin(), events_.end(), [&](const SessionEvent& e) { return e.kind == kind; }));
    }

    fs::path dir_;
    std::mutex mutex_;
    std::vector<SessionEvent> events_;
};

inline ScannerOpener tof_opener(std::shared_ptr<sim::SimDeviceFaults> faults, int* opened) {
    return [faults, opened]() -> Expected<std::unique_ptr<drivers::Scanner>> {
        ++*opened;
        // Faults only on the first device: the one plugged in again works.
        return std::unique_ptr<drivers::Scanner>(
            sim::SimTofScanner::open(sim::test::small_tof_config(*opened == 1 ? faults : nullptr)));
    };
}

}  // namespace anascan::acquisition
