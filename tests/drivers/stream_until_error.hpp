#pragma once
// Streams a camera on its StreamRunner until the stream reports an error (or a time
// limit passes, or enough frames came), then stops it: what the unplug, garbage and frozen
// frame tests of every backend need.

#include <chrono>
#include <condition_variable>
#include <functional>
#include <mutex>
#include <optional>
#include <vector>

#include "anascan/drivers/stream_runner.hpp"

namespace anascan::drivers::test {

struct StreamEnd {
    bool started = false;
    std::optional<Error> error;  ///< Empty when the limit passed first.
    std::uint64_t frames = 0;
    std::uint64_t dropped = 0;    ///< Unreadable frames the runner dropped.
    std::vector<Error> warnings;  ///< What the runner reported and survived.
};

/// Streams until an error, `limit`, or (when not 0) `stop_after_frames` delivered frames.
inline StreamEnd stream_until_error(Camera& camera, std::chrono::seconds limit,
                                    const StreamRunnerConfig& config = {},
                                    std::function<void(const Frame&)> on_frame = {},
                                    std::uint64_t stop_after_frames = 0) {
    std::mutex m;
    std::condition_variable cv;
    StreamEnd end;
    std::uint64_t delivered = 0;
    auto runner = StreamRunner::start(camera,
                                      {.on_frame =
                                           [&](const Frame& f) {
                                               if (on_frame) on_frame(f);
                                               std::lock_guard lock(m);
                                               ++delivered;
                                               cv.notify_all();
                                           },
                                       .on_error =
                                           [&](const Error& e) {
                                               std::lock_guard lock(m);
                                               end.error = e;
                                               cv.notify_all();
                                           },
                                       .on_warning =
                                           [&](const Error& e) {
                                               std::lock_guard lock(m);
                                               end.warnings.push_back(e);
                                           }},
                                      config);
    if (!runner) {
        end.error = runner.error();
        return end;
    }
    end.started = true;
    {
        std::unique_lock lock(m);
        cv.wait_for(lock, limit, [&] {
            return end.error.has_value() ||
                   (stop_after_frames > 0 && delivered >= stop_after_frames);
        });
    }
    (*runner)->stop();
    end.frames = (*runner)->frames_delivered();
    end.dropped = (*runner)->frames_dropped();
    return end;
}

}  // namespace anascan::drivers::test
