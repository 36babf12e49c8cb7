#pragma once
// The pixel values every test device (scripted, mocked V4L2, mocked USB) delivers.

#include <cstdint>

namespace anascan::drivers::test {

/// Value at (row, col) of frame `sequence` (Z16 device units; 8-bit formats: low byte).
inline std::uint16_t mock_pixel(int row, int col, std::uint64_t sequence) {
    return static_cast<std::uint16_t>(1000 + 10 * row + col + 3 * sequence);
}

}  // namespace anascan::drivers::test
