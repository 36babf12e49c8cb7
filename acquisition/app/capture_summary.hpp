#pragma once
// What `anascan capture` and `anascan session register` print and store at the end:
// scans by state, groups, latency, coverage.

#include "anascan/acquisition/capture/capture_session.hpp"
#include "anascan/acquisition/store/session_store.hpp"

namespace anascan::cli {

/// Prints scans by state, groups, median and 95th-percentile latency (acknowledged to
/// registered) and the coverage, from the session's records.
void print_capture_summary(const acquisition::SessionStore& store);

/// Prints the session's events, one line each, as they arrive: progress on stdout,
/// failures once, as errors on stderr.
acquisition::SessionEventSink printing_sink();

/// The coverage of the finished session, from the scans on disk as `anascan coverage`
/// computes it, so that both report the same figure.
void store_final_coverage(acquisition::SessionStore& store);

}  // namespace anascan::cli
