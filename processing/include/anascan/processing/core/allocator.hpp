#pragma once
// Process-wide allocator setting for long registrations (see docs/scan-registration.md,
// "Scale"). The library never calls this itself: it is the application's choice (the
// `register` command and the scale benchmark call it once at start-up).
#include <cstddef>

namespace anascan {

/// Default block size from which glibc serves allocations by their own mapping (bytes).
inline constexpr std::size_t kFixedMmapThresholdBytes = 128 * 1024;

/// Fixes glibc's mmap threshold and trim threshold at `threshold_bytes`: every block of at
/// least that size gets its own mapping, returned to the system when freed, and free memory
/// at the top of the heap beyond it is trimmed. By default glibc raises the mmap threshold
/// to the largest block freed so far (up to 32 MB), so after the first large frees later
/// per-scan buffers come from the heap arenas and fragment them: peak RSS then grows with
/// the number of scans while the live data does not. Returns false when the C library does
/// not support the setting (non-glibc); nothing is changed then.
bool use_fixed_mmap_threshold(std::size_t threshold_bytes = kFixedMmapThresholdBytes);

}  // namespace anascan
