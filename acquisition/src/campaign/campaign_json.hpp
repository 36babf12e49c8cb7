#pragma once
// JSON forms of the campaign stages' results, as stored and as sent between ranks.
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "anascan/processing/campaign/campaign_stages.hpp"

namespace anascan::acquisition::campaign_json {

nlohmann::json pose(const Pose& T);  ///< 4x4 row-major.
Pose pose_from(const nlohmann::json& rows);

nlohmann::json summary(const PreparedSummary& s);
PreparedSummary summary_from(const nlohmann::json& j);

/// A pair task's output (written by campaign_tasks.cpp, which also names the status).
CampaignPairResult pair_from(const nlohmann::json& j);

}  // namespace anascan::acquisition::campaign_json

namespace anascan::acquisition {
class CampaignStore;
struct CampaignScanRow;
}  // namespace anascan::acquisition

namespace anascan::acquisition::campaign_json {

/// A damaged stored value, named: "DIR/campaign.sqlite: WHAT: PROBLEM (WHAT may be empty) (run
/// `anascan campaign check DIR --repair`...)".
Error damaged(const CampaignStore& store, const std::string& what, const Error& problem);

/// Every stored summary and result reads with the checked readers (campaign_results.hpp);
/// after this the job's own readers of the same values cannot fail.
Expected<void> verify_stored(const CampaignStore& store, const std::vector<CampaignScanRow>& scans);

}  // namespace anascan::acquisition::campaign_json
