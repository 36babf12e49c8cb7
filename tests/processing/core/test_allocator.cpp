#include <gtest/gtest.h>

#include <vector>

#include "anascan/processing/core/allocator.hpp"

namespace anascan {
namespace {

TEST(Allocator, AFixedMmapThresholdIsSetOnGlibcAndNonsenseIsRefused) {
    EXPECT_FALSE(use_fixed_mmap_threshold(0));
#if defined(__GLIBC__) && !defined(__SANITIZE_ADDRESS__)
    EXPECT_TRUE(use_fixed_mmap_threshold());
    std::vector<char> block(4 * kFixedMmapThresholdBytes, 'x');  // Served by its own mapping.
    EXPECT_EQ(block.back(), 'x');
#else  // Not glibc's malloc: AddressSanitizer's mallopt sets nothing and says so.
    EXPECT_FALSE(use_fixed_mmap_threshold());
#endif
}

}  // namespace
}  // namespace anascan
