#pragma once
/// \file
/// The UI thread polls futures without waiting.

#include <chrono>
#include <future>
#include <optional>

namespace anascan::field {

/// True when the future exists and its result is ready.
template <typename T>
bool ready(const std::optional<std::future<T>>& future) {
    return future && future->wait_for(std::chrono::seconds(0)) == std::future_status::ready;
}

}  // namespace anascan::field
