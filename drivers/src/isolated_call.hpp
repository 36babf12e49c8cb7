#pragma once
// A function run in a child process, with a time limit and a crash boundary: for parsers of
// outside files that may never return or may crash (OpenCV's FileStorage, docs/reliability.md).

#include <chrono>
#include <functional>
#include <optional>
#include <string>
#include <string_view>

#include "anascan/processing/core/expected.hpp"

namespace anascan::drivers {

/// What an isolated call works on, for its messages, and how long it may run.
struct IsolatedCallConfig {
    std::string subject;  ///< Named first in every error: the file, "calib.yml".
    std::string worker;   ///< What runs in the child: "the calibration parser".
    std::chrono::milliseconds time_limit{3000};
};

/// Runs `work` in a child process (fork) and returns the bytes it returned. The child
/// resets the crash signals to their default action, closes every descriptor but its end of
/// the pipe and stdin/stdout/stderr, runs `work`, writes the bytes and leaves with `_exit`
/// (no atexit handlers, no destructors of the parent's objects). Only the forking thread
/// exists in the child: `work` must not wait for another thread. A lock that another thread
/// held at the fork stays taken in the child; the time limit bounds that case too.
/// The parent waits at most `time_limit`, then kills (SIGKILL) and reaps the child. Errors
/// start with "<subject>: <worker>": "did not finish within 3 s (malformed file?)"
/// (kTimeout), "crashed (signal SIGSEGV) on this file", "exited with status N", "sent a
/// truncated result" (kFormat); kIo when no child could be started (pipe, fork). No child
/// and no descriptor outlives the call. Thread-safe: each call has its own pipe and child,
/// and the child is waited for by its pid only.
Expected<std::string> call_isolated(const IsolatedCallConfig& config,
                                    const std::function<std::string()>& work);

/// The pipe's format: the payload's length (8 bytes, this machine's order), then the payload.
std::string frame_message(std::string_view payload);

/// The payload of a complete frame; empty when `bytes` is shorter or longer than its header
/// announces.
std::optional<std::string_view> unframe_message(std::string_view bytes);

}  // namespace anascan::drivers
