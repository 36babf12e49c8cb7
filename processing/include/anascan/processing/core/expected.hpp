#pragma once
/// \file
/// `anascan::Expected<T>`: the result of an operation that can fail for reasons outside the
/// program (a file, a device). It is `std::expected<T, Error>` (C++23).
///
/// Why a header for one alias: clang 14, which builds our libFuzzer targets, cannot compile
/// libstdc++ 12's <expected> (it needs P0848 conditionally trivial destructors). For that
/// build only, a minimal stand-in with the same member names is used; see docs/expected.md.
/// Code always writes `Expected<T>` and `return fail(...)` so it compiles in both.

#include <version>

#if defined(__cpp_lib_expected)
#include <expected>
#define ANASCAN_STD_EXPECTED 1
#else
#include "anascan/processing/core/detail/expected_fallback.hpp"
#define ANASCAN_STD_EXPECTED 0
#endif

#include "anascan/processing/core/error.hpp"

namespace anascan {

#if ANASCAN_STD_EXPECTED
template <class T, class E = Error>
using Expected = std::expected<T, E>;
template <class E>
using Unexpected = std::unexpected<E>;
#else
template <class T, class E = Error>
using Expected = detail::Expected<T, E>;
template <class E>
using Unexpected = detail::Unexpected<E>;
#endif

/// Builds the error branch of an `Expected`: `return fail(ErrorCode::kFormat, "...")`.
inline Unexpected<Error> fail(ErrorCode code, std::string message) {
    return Unexpected<Error>(Error{code, std::move(message)});
}

/// Passes an existing error on unchanged.
inline Unexpected<Error> fail(Error error) { return Unexpected<Error>(std::move(error)); }

}  // namespace anascan
