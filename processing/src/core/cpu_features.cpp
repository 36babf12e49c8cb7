#include "core/cpu_features.hpp"

#include <cstdlib>

namespace anascan::detail {

bool cpu_has_avx2() {
#if defined(__x86_64__) && defined(__GNUC__)
    static const bool avx2 =
        __builtin_cpu_supports("avx2") && std::getenv("ANASCAN_DISABLE_AVX2") == nullptr;
    return avx2;
#else
    return false;
#endif
}

}  // namespace anascan::detail
