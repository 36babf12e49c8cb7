#pragma once
// The end-of-session summary of `anascan capture`: scans by state, groups, latency.

#include "anascan/acquisition/session_store.hpp"

namespace anascan::cli {

/// Prints scans by state, groups, median and 95th-percentile latency (acknowledged to
/// registered) and the coverage, from the session's records.
void print_capture_summary(const acquisition::SessionStore& store);

}  // namespace anascan::cli
