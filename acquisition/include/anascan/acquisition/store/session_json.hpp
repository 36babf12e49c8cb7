#pragma once
/// \file
/// The session as JSON: the document of `anascan session info --json`.
///
/// {"session": DIR, "schema_version": 2,
///  "scans": [{"seq", "file", "state", "group", "pose": [16] | null, "true_pose": [16] | null,
///             "latency_s": s | null, "excluded", "device_id", "device_kind", "points",
///             "captured_at": ISO-8601 UTC, "turned_over_before", "file_problem",
///             "quality": object | null}],
///  "coverage": fraction | null (the "fraction" of the stored value "coverage"),
///  "coverage_report": the stored value "coverage" | null,
///  "devices": [{"id", "kind"}], "events": count, "notes": [{"seq" | null, "text", "time"}]}
/// Poses are row-major T_world_scan (world = the frame of the scan's group), metres.

#include <string>

#include "anascan/acquisition/store/session_store.hpp"

namespace anascan::acquisition {

/// ISO-8601 UTC with milliseconds, e.g. "2026-11-22T13:35:49.123Z".
std::string format_utc(TimePoint t);

/// The stored coverage fraction (value "coverage", its "fraction"), if any.
Expected<std::optional<double>> coverage_fraction(const SessionStore& store);

/// The whole session document (pretty-printed with `indent` spaces, -1 for one line).
Expected<std::string> session_info_json(const SessionStore& store, int indent = 2);

}  // namespace anascan::acquisition
