#pragma once
// Integers from a JSON file written elsewhere. nlohmann's get<integer>() converts a JSON
// floating-point number with a static_cast, which is undefined behaviour out of range (a
// scan record's "time_ns": 1.7e20, found by fuzz_recording). Only a JSON integer that fits
// the type is taken; anything else throws json::type_error, which the readers turn into an
// error naming the file.
#include <cstdint>
#include <limits>
#include <nlohmann/json.hpp>
#include <type_traits>

namespace anascan::drivers {

template <typename T>
T json_integer(const nlohmann::json& value) {
    static_assert(std::is_integral_v<T> && std::is_signed_v<T>);
    bool fits = false;
    if (value.is_number_unsigned()) {
        fits = value.get<std::uint64_t>() <= std::uint64_t(std::numeric_limits<T>::max());
    } else if (value.is_number_integer()) {
        const auto v = value.get<std::int64_t>();
        fits = v >= std::int64_t(std::numeric_limits<T>::min()) &&
               v <= std::int64_t(std::numeric_limits<T>::max());
    }
    if (!fits) {
        throw nlohmann::json::type_error::create(
            302, "expected an integer within range, found " + value.dump(), &value);
    }
    return value.get<T>();
}

}  // namespace anascan::drivers
