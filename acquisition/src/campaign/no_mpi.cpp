// Built without MPI: campaigns run in one process.
#include "anascan/acquisition/campaign/campaign_job.hpp"

namespace anascan::acquisition {

bool campaign_mpi_launched() { return false; }

std::unique_ptr<CampaignExecutor> make_mpi_executor(const CampaignConfig& config, int& rank) {
    rank = 0;
    return make_local_executor(config);
}

void serve_campaign_tasks(const CampaignConfig&) {}

}  // namespace anascan::acquisition
