// use_fixed_mmap_threshold: glibc's mallopt, nothing elsewhere.
#include "anascan/processing/core/allocator.hpp"

#include <climits>

#if defined(__GLIBC__)
#include <malloc.h>
#endif

namespace anascan {

bool use_fixed_mmap_threshold(std::size_t threshold_bytes) {
#if defined(__GLIBC__)
    if (threshold_bytes == 0 || threshold_bytes > static_cast<std::size_t>(INT_MAX)) return false;
    const int bytes = static_cast<int>(threshold_bytes);
    return mallopt(M_MMAP_THRESHOLD, bytes) == 1 && mallopt(M_TRIM_THRESHOLD, bytes) == 1;
#else
    (void)threshold_bytes;
    return false;
#endif
}

}  // namespace anascan
