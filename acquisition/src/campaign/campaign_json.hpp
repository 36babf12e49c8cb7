#pragma once
// JSON forms of the campaign stages' results, as stored and as sent between ranks.
#include <nlohmann/json.hpp>

#include "anascan/processing/campaign/campaign_stages.hpp"

namespace anascan::acquisition::campaign_json {

nlohmann::json pose(const Pose& T);  ///< 4x4 row-major.
Pose pose_from(const nlohmann::json& rows);

nlohmann::json summary(const PreparedSummary& s);
PreparedSummary summary_from(const nlohmann::json& j);

nlohmann::json pair(const CampaignPairResult& r);
CampaignPairResult pair_from(const nlohmann::json& j);

}  // namespace anascan::acquisition::campaign_json
