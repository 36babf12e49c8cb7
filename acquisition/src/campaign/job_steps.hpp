#pragma once
// Internal steps of run_campaign shared by its source files.
#include <functional>
#include <string>
#include <vector>

#include "anascan/acquisition/campaign/campaign_job.hpp"

namespace anascan::acquisition::campaign_steps {

using Progress = std::function<void(const CampaignProgress&)>;

/// One job's executor, progress callback and counts.
struct StageRun {
    CampaignExecutor& executor;
    const Progress& progress;
    CampaignJobReport& report;
};

/// Runs `tasks` (the stage's unfinished ones; `done_before` were finished) through the
/// executor, `sink` recording each result; reports progress after each.
Expected<void> run_stage(StageRun& run, const std::string& name, std::vector<CampaignTask> tasks,
                         std::size_t done_before, const CampaignExecutor::Sink& sink);

/// The scan's stored summary (empty before preparation).
PreparedSummary summary_of(const CampaignScanRow& row);

/// The match graph (stones, once) and the multi-view stage (per stone).
Expected<void> stone_stages(StageRun& run, CampaignStore& store,
                            const std::vector<CampaignScanRow>& scans,
                            const CampaignConfig& config);

}  // namespace anascan::acquisition::campaign_steps
