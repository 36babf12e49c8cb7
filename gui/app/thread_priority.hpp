#pragma once
/// \file
/// The UI thread before the work threads: capture, persistence and registration (and the
/// scan loads of the view) run at a lower CPU priority than the thread that draws, so that
/// on a small laptop a registration in progress does not slow the view down. Linux keeps a
/// nice value per thread and a new thread inherits its creator's: starting a
/// CaptureSession from a lowered helper thread lowers every thread it starts (its scanner,
/// save and registration threads, and the TBB workers registration starts), with no change
/// to acquisition. The UI thread and Mesa's llvmpipe threads keep their priority.

#include <optional>
#include <thread>
#include <type_traits>
#include <utility>

namespace anascan::field {

/// Raises the calling thread's nice value by `increment` (0: no change). Lowering one's
/// own priority needs no privilege; returns false when the system refused (never fatal).
bool lower_this_thread_priority(int increment);

/// Runs `f` on a helper thread lowered by `increment`, waits for it and returns its result:
/// the threads `f` starts inherit the lower priority.
template <typename F>
std::invoke_result_t<F> call_at_lower_priority(int increment, F&& f) {
    std::optional<std::invoke_result_t<F>> result;
    std::thread helper([&] {
        lower_this_thread_priority(increment);
        result.emplace(std::forward<F>(f)());
    });
    helper.join();
    return std::move(*result);
}

}  // namespace anascan::field
