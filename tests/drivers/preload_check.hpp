#pragma once
// Whether this process runs under umockdev-wrapper (the mocked-device tests skip otherwise).

#include <cstdlib>
#include <cstring>

namespace anascan::drivers::test {

/// True when the umockdev preload library is loaded (LD_PRELOAD).
inline bool umockdev_preloaded() {
    const char* preload = std::getenv("LD_PRELOAD");
    return preload != nullptr && std::strstr(preload, "umockdev-preload") != nullptr;
}

}  // namespace anascan::drivers::test
