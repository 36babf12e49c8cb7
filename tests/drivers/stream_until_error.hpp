#pragma once
// Streams a camera on its StreamRunner until the stream reports an error (or a time
// limit passes), then stops it: what the unplug tests of every backend need.

#include <chrono>
#include <condition_variable>
#include <functional>
#include <mutex>
#include <optional>

#include "anascan/drivers/stream_runner.hpp"

namespace anascan::drivers::test {

struct StreamEnd {
    bool started = false;
    std::optional<Error> error;  ///< Empty when the limit passed first.
    std::uint64_t frames = 0;
};

inline StreamEnd stream_until_error(Camera& camera, std::chrono::seconds limit,
                                    const StreamRunnerConfig& config = {},
                                    std::function<void(const Frame&)> on_frame = {}) {
    std::mutex m;
    std::condition_variable cv;
    StreamEnd end;
    auto runner = StreamRunner::start(camera,
                                      {.on_frame =
                                           [&](const Frame& f) {
                                               if (on_frame) on_frame(f);
                                           },
                                       .on_error =
                                           [&](const Error& e) {
                                               std::lock_guard lock(m);
                                               end.error = e;
                                               cv.notify_all();
                                           }},
                                      config);
    if (!runner) {
        end.error = runner.error();
        return end;
    }
    end.started = true;
    {
        std::unique_lock lock(m);
        cv.wait_for(lock, limit, [&] { return end.error.has_value(); });
    }
    (*runner)->stop();
    end.frames = (*runner)->frames_delivered();
    return end;
}

}  // namespace anascan::drivers::test
