#include <gtest/gtest.h>

#include "anascan/processing/core/median.hpp"

namespace anascan {
namespace {

TEST(UpperMedian, IsTheMiddleOrTheUpperOfTheTwoMiddlesAndZeroWhenEmpty) {
    EXPECT_EQ(upper_median({3.0, 1.0, 2.0}), 2.0);
    EXPECT_EQ(upper_median({4.0, 1.0, 3.0, 2.0}), 3.0);
    EXPECT_EQ(upper_median({5.0}), 5.0);
    EXPECT_EQ(upper_median({}), 0.0);
}

}  // namespace
}  // namespace anascan
