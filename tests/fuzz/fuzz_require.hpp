#pragma once
// The fuzz harnesses' checks: a broken expectation aborts, so libFuzzer keeps the input.
#include <cstdlib>

#include "anascan/processing/core/expected.hpp"

namespace anascan::fuzz {

inline void require(bool condition) {
    if (!condition) std::abort();
}

/// A failure must say what failed.
template <typename T>
void require_message(const Expected<T>& result) {
    if (!result) require(!result.error().message.empty());
}

}  // namespace anascan::fuzz
