#pragma once
// Shared by the `campaign` sub-commands.
#include <CLI/CLI.hpp>

#include "anascan/acquisition/campaign/campaign_store.hpp"
#include "anascan/processing/campaign/campaign_stages.hpp"

namespace anascan::cli {

/// The campaign's settings: defaults with what `campaign init` recorded.
CampaignConfig stored_config(const acquisition::CampaignStore& store);

/// Prints the stages' counts, the stones and the scans not used (stdout).
void print_status(const acquisition::CampaignStore& store);

/// `campaign status`, `campaign export` and `campaign check`.
void add_campaign_status_commands(CLI::App& campaign);

/// Hidden `campaign eval DIR --truth TRUTH.json`.
void add_campaign_eval_command(CLI::App& campaign);

}  // namespace anascan::cli
