#pragma once
// What a test checks is left behind by code that forks: descriptors, threads, children.

#include <sys/wait.h>

#include <cerrno>
#include <chrono>
#include <cstddef>
#include <filesystem>
#include <thread>

namespace anascan::drivers::test {

inline std::size_t entries_in(const std::filesystem::path& dir) {
    std::size_t n = 0;
    for ([[maybe_unused]] const auto& e : std::filesystem::directory_iterator(dir)) ++n;
    return n;
}
inline std::size_t open_descriptors() { return entries_in("/proc/self/fd"); }
inline std::size_t threads() { return entries_in("/proc/self/task"); }

/// The thread count once it is down to `expected` or a second has passed: a joined thread
/// may stay listed for a moment while the kernel ends it.
inline std::size_t threads_settled_to(std::size_t expected) {
    for (int i = 0; i < 100 && threads() > expected; ++i)
        std::this_thread::sleep_for(std::chrono::milliseconds(10));
    return threads();
}

/// Whether this process has a child, running or a zombie (a zombie found is reaped).
inline bool has_child() { return !(::waitpid(-1, nullptr, WNOHANG) < 0 && errno == ECHILD); }

}  // namespace anascan::drivers::test
