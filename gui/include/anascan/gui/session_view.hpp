#pragma once
/// \file
/// The session as the field app shows it: scan rows from acquisition's ScanRecords, the
/// stored coverage (fraction and holes) from its JSON, the group the 3D view draws, and a
/// one-line summary of what `session check` found. Plain functions, no GL, no threads.

#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "anascan/acquisition/store/session_check.hpp"
#include "anascan/acquisition/store/session_store.hpp"
#include "anascan/gui/field_view_state.hpp"
#include "anascan/gui/point_renderer.hpp"

namespace anascan::gui {

/// One scan-list row: seq, device, time, state and group one to one; RMS (mm) and overlap
/// (%) from the registrar's quality_json ("rms_m", "overlap_fraction"); the message from it
/// ("message", else "reason") or the file problem found by `session check`. A scan placed
/// without a registration ("method" "first" or "new-group") has no RMS and no overlap.
ScanRow scan_row(const acquisition::ScanRecord& record);

/// Registered rows alone in their group (no other registered, non-excluded row with them)
/// become kUnjoined: they joined nothing, whatever their figures say.
void mark_unjoined(std::vector<ScanRow>& rows);

/// The stored value "coverage" (coverage_to_json, read by coverage_from_json): its
/// fraction and its holes as markers.
struct StoredCoverage {
    std::optional<double> fraction;  ///< 0..1; absent when the JSON has none.
    std::vector<HoleMarker> holes;
};

/// Parses the coverage JSON; malformed text gives an empty result (no figure, no holes).
StoredCoverage parse_coverage_json(std::string_view json);

/// The group the view draws: the one with the most registered, non-excluded scans with a
/// pose (lowest id on a tie), as `session_coverage` chooses; -1 when none.
int model_group(const std::vector<acquisition::ScanRecord>& scans);

/// True when the scan's points belong in the 3D view (registered in `group`, with a pose).
bool drawn_in_view(const acquisition::ScanRecord& record, int group);

/// What the operator reads when a capture failed (acquisition's error): a device that went
/// away or did not answer, a full disk, a folder that cannot be written, anything else.
/// The message keeps acquisition's text (it names the device or the session folder).
CaptureProblem capture_problem(const Error& error);

/// Empty when the check found nothing; else one line for the device panel ("2 problems:
/// scans/scan_000003.ply: ...; run `anascan session check DIR --repair`").
std::string check_summary(const acquisition::SessionCheckReport& report);

}  // namespace anascan::gui
