#pragma once
/// \file
/// The stored results of a campaign, read back with every value checked: a campaign folder
/// may have been damaged (a bit flip, another tool's edit), and nothing that reads it may
/// crash or index out of range. Each reader fails kFormat naming what is damaged; `campaign
/// check` uses the same readers, so it finds exactly what the job and `status` would trip on.
#include <cstddef>
#include <cstdint>
#include <map>
#include <optional>
#include <string>
#include <vector>

#include "anascan/acquisition/campaign/campaign_store.hpp"
#include "anascan/processing/campaign/campaign_stages.hpp"

namespace anascan::acquisition {

/// A scan's prepared summary (`CampaignScanRow::summary_json`; empty text: none yet).
Expected<PreparedSummary> read_scan_summary(const std::string& json);

/// A pair's registration; nullopt when the pair's registration failed and the failure is the
/// recorded result (`{"error": ...}`).
Expected<std::optional<CampaignPairResult>> read_pair_result(const std::string& json);

/// One scan of a stone's multi-view result.
struct CampaignStoneScan {
    std::int64_t id = 0;
    bool placed = false;
    Pose T_stone_scan = Pose::Identity();
    std::string reason, warning;
};

struct CampaignStoneResult {
    std::vector<CampaignStoneScan> scans;
    std::size_t placed = 0;
};

/// A stone's multi-view result; every scan id must be below `scan_count`.
Expected<CampaignStoneResult> read_stone_result(const std::string& json, std::size_t scan_count);

/// The match graph's warnings by scan id (the `graph` value; empty text: none yet).
Expected<std::map<std::int64_t, std::string>> read_graph_warnings(const std::string& json,
                                                                  std::size_t scan_count);

/// What `campaign status` shows: the stages' counts and the scans not used or not placed.
struct CampaignStatus {
    std::size_t scans = 0, prepared = 0, described = 0, unusable = 0;
    std::size_t pairs = 0, registered = 0, verified = 0;
    std::size_t stones = 0, stones_done = 0, placed = 0;
    std::vector<std::string> problems;  ///< "not used: FILE: why", "not placed (stone K)...".
};

Expected<CampaignStatus> campaign_status(const CampaignStore& store);

}  // namespace anascan::acquisition
