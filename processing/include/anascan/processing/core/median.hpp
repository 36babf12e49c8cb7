#pragma once
/// \file
/// The median of a list of figures, as the session gates and the multi-view rule use it.
#include <algorithm>
#include <cstddef>
#include <vector>

namespace anascan {

/// The upper median (element n/2 in sorted order) of `values`; 0 when empty. Takes a copy:
/// the order is the caller's.
inline double upper_median(std::vector<double> values) {
    if (values.empty()) return 0.0;
    const auto middle = values.begin() + static_cast<std::ptrdiff_t>(values.size() / 2);
    std::nth_element(values.begin(), middle, values.end());
    return *middle;
}

}  // namespace anascan
