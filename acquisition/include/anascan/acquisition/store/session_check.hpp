#pragma once
/// \file
/// `session check`: verifies a session folder against its database after a crash or a
/// disk problem, and repairs what can be repaired without losing anything acknowledged.
///
/// - every scan row: its file exists, has the CRC-32 recorded at acknowledgement (bit flips,
///   torn writes), parses as PLY and holds the recorded point count;
///   a damaged file of an acknowledged scan is reported with its path; repair marks the row
///   failed with the reason (file and row are kept, never deleted);
/// - temporary files of interrupted writes (`scans/.scan_*.ply.tmp*`): removed on repair;
/// - final scan files without a row (a crash between rename and commit: never acknowledged):
///   moved to `DIR/recovered/` on repair, not added to the session;
/// - the database: opening it replays the WAL; `PRAGMA integrity_check`; repair folds the
///   WAL into the database file.

#include <cstdint>
#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include "anascan/processing/core/expected.hpp"

namespace anascan::acquisition {

struct SessionCheckOptions {
    bool repair = false;
};

enum class CheckIssueKind {
    kMissingFile,         ///< A row's file does not exist.
    kDamagedFile,         ///< Wrong CRC-32, does not parse or has the wrong point count.
    kTemporaryFile,       ///< Left by an interrupted write.
    kUnacknowledgedFile,  ///< A final scan file without a row.
    kDatabase,            ///< integrity_check found problems.
};

/// "missing-file", "damaged-file", "temporary-file", "unacknowledged-file", "database".
std::string_view to_string(CheckIssueKind kind);

struct CheckIssue {
    CheckIssueKind kind = CheckIssueKind::kDamagedFile;
    std::optional<std::int64_t> seq;  ///< The scan row concerned, if any.
    std::filesystem::path file;       ///< The file concerned (absolute or as given + relative).
    std::string problem;              ///< What is wrong.
    bool repaired = false;            ///< Repaired by this run.
    bool recorded = false;            ///< Already recorded in the database by an earlier repair.
    std::string action;               ///< What repair did or would do.
};

struct SessionCheckReport {
    std::filesystem::path dir;
    int schema_version = 0;
    std::size_t scans_checked = 0;
    std::size_t scans_ok = 0;
    std::size_t scans_without_checksum = 0;  ///< Intact, saved before CRC-32s were recorded.
    std::size_t checksums_recorded = 0;      ///< Of those, recorded by this --repair run.
    std::string integrity = "ok";            ///< PRAGMA integrity_check's answer.
    std::vector<CheckIssue> issues;

    /// Issues neither repaired nor already recorded.
    std::size_t unresolved() const;
    bool clean() const { return unresolved() == 0; }
    /// One line per finding and a summary, for the terminal.
    std::vector<std::string> lines() const;
};

/// Checks (and with `repair` repairs) the session in `dir`. Errors only when the folder or
/// its database cannot be opened at all (the message names it and says what to do).
Expected<SessionCheckReport> check_session(const std::filesystem::path& dir,
                                           const SessionCheckOptions& options = {});

}  // namespace anascan::acquisition
