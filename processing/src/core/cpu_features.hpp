#pragma once
/// \file
/// Private: which optional instruction sets the hot loops may use (checked once).

namespace anascan::detail {

/// Whether this CPU runs AVX2 code (x86-64 with GCC or Clang), and the environment does
/// not set ANASCAN_DISABLE_AVX2 (so that the tests can run the portable paths too; the
/// results are the same either way).
bool cpu_has_avx2();

}  // namespace anascan::detail
