#pragma once
// Looking for text in a command's output.
#include <cstddef>
#include <string>

namespace anascan::testing_util {

inline bool contains(const std::string& text, const std::string& part) {
    return text.find(part) != std::string::npos;
}

/// How many times `part` occurs in `text` (overlapping occurrences count).
inline std::size_t occurrences(const std::string& text, const std::string& part) {
    std::size_t n = 0;
    for (std::size_t at = text.find(part); at != std::string::npos; at = text.find(part, at + 1))
        ++n;
    return n;
}

}  // namespace anascan::testing_util
