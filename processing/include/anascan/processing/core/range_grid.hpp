#pragma once
/// \file
/// The 2-D sample grid of a range scanner (Stanford `range_grid`, PTX rows and columns):
/// which point, if any, each scanner pixel produced, so neighbours can be found by index.

#include <cstdint>
#include <vector>

namespace anascan {

/// Row-major grid of point indices; `kNoSample` where the scanner got no return.
struct RangeGrid {
    static constexpr std::int32_t kNoSample = -1;
    int rows = 0;
    int cols = 0;
    std::vector<std::int32_t> point_index;  ///< rows*cols entries.

    std::int32_t at(int row, int col) const { return point_index[row * cols + col]; }
};

}  // namespace anascan
