#pragma once
/// \file
/// `campaign check`: verifies a campaign folder after a kill or a disk problem, and repairs
/// what can be repaired so that `campaign register` redoes exactly the damaged work.
///
/// - the database: opening it replays the WAL; `PRAGMA integrity_check`;
/// - every prepared or described scan: its prepared cloud (`prepared/scan_N.ply`) exists,
///   parses as PLY and holds the point count of its stored summary; repair sets the scan
///   back to `new`, so the next run prepares and describes it again (both are
///   deterministic: the candidates and pair results already made stay valid);
/// - every scan's state and prepared summary, every stored pair and stone result and the
///   match graph read with the checked readers of campaign_results.hpp (the same as the job
///   and `status` use); repair sets a damaged scan back to `new`, clears a damaged result (the
///   next run registers that pair, or refines that stone, again) and forgets damaged stones
///   and graph (found again from the pairs);
/// - tables whose rows contradict each other (a pair naming a scan that does not exist):
///   reported, not repairable;
/// - temporary files of interrupted writes (`prepared/.scan_N.ply.tmp*`): harmless (never
///   under a final name), listed and removed on repair; they do not make the check fail.

#include <cstdint>
#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include "anascan/processing/core/expected.hpp"

namespace anascan::acquisition {

struct CampaignCheckIssue {
    /// "database", "scan-record", "prepared-cloud", "pair-result", "stone-result",
    /// "match-graph" or "temporary-file".
    std::string kind;
    std::optional<std::int64_t> id;  ///< The scan or stone concerned, if any.
    std::filesystem::path file;      ///< The file concerned, if any.
    std::string problem;
    std::string action;  ///< What repair did or would do.
    bool repaired = false;
};

struct CampaignCheckReport {
    std::filesystem::path dir;
    std::string integrity = "ok";  ///< PRAGMA integrity_check's answer.
    std::size_t prepared_checked = 0, prepared_ok = 0;
    std::size_t results_checked = 0;  ///< Pair and stone results.
    std::vector<CampaignCheckIssue> issues;

    /// Damage neither repaired nor harmless (temporary files do not count).
    std::size_t unresolved() const;
    bool clean() const { return unresolved() == 0; }
    /// One line per finding and a summary, for the terminal.
    std::vector<std::string> lines() const;
};

/// Checks (and with `repair` repairs) the campaign in `dir`. Errors only when the folder or
/// its database cannot be opened (a running job holds the lock when repairing: kBusy).
Expected<CampaignCheckReport> check_campaign(const std::filesystem::path& dir, bool repair);

}  // namespace anascan::acquisition
