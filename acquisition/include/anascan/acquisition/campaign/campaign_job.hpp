#pragma once
/// \file
/// A campaign job: the stages of processing/campaign as sets of independent tasks, run by
/// an executor (this process, or MPI ranks) while the store records every result as it
/// arrives. A rerun runs only what is not stored yet.
///
/// Stages in order: prepare (per scan), describe (per scan), candidates (once, on the
/// owner of the store), pairs (per candidate pair), stones (once), multiview (per stone).
///
/// Thread safety: `run_campaign` is not reentrant on one store; executors are used by one
/// thread.
#include <cstdint>
#include <functional>
#include <memory>
#include <string>
#include <vector>

#include "anascan/acquisition/campaign/campaign_store.hpp"
#include "anascan/processing/campaign/campaign_stages.hpp"

namespace anascan::acquisition {

enum class CampaignTaskKind : int { kPrepare = 1, kDescribe = 2, kPair = 3, kStone = 4 };

/// One task: what to do (JSON naming the files it needs) and its estimated cost (larger
/// first).
struct CampaignTask {
    CampaignTaskKind kind = CampaignTaskKind::kPrepare;
    std::int64_t id = 0;  ///< Scan, pair or stone number, for the owner.
    std::string input_json;
    double cost = 0.0;
};

/// A task's result: JSON figures and, for descriptors, the keys as bytes.
struct CampaignTaskResult {
    CampaignTaskKind kind = CampaignTaskKind::kPrepare;
    std::int64_t id = 0;
    std::string output_json;
    std::vector<unsigned char> blob;
};

/// Runs one task on any rank: reads the files its input names (and, for prepare, writes
/// the prepared cloud where the input says). Never throws; a failure is in the output:
/// `error` for the user's scan (recorded), `store_error` for the campaign's own files
/// (writing or reading a prepared cloud: the job stops and records nothing).
CampaignTaskResult run_campaign_task(const CampaignTask& task, const CampaignConfig& config);

/// Runs tasks somewhere and hands each result to `sink` on the calling thread, in any
/// order. Stops at the first sink failure and returns it.
class CampaignExecutor {
public:
    virtual ~CampaignExecutor() = default;
    using Sink = std::function<Expected<void>(CampaignTaskResult)>;
    virtual Expected<void> run(std::vector<CampaignTask> tasks, const Sink& sink) = 0;
    /// Processes running tasks (1 for this process alone).
    virtual int ranks() const = 0;
};

/// Runs every task in this process, largest first.
std::unique_ptr<CampaignExecutor> make_local_executor(const CampaignConfig& config);

/// Progress of a stage: tasks done of total (this run and before), rate and ETA.
struct CampaignProgress {
    std::string stage;
    std::size_t done = 0, total = 0;
    std::size_t done_before = 0;  ///< Found finished in the store at the start.
    double rate_per_s = 0.0;      ///< Tasks per second in this run.
    double eta_s = 0.0;
};

/// Per stage: tasks found finished and tasks run now.
struct CampaignStageCount {
    std::string stage;
    std::size_t already_done = 0, run_now = 0;
};

struct CampaignJobReport {
    std::vector<CampaignStageCount> stages;
};

/// Runs the stages not finished yet; `progress` (may be empty) after every result.
Expected<CampaignJobReport> run_campaign(
    CampaignStore& store, CampaignExecutor& executor, const CampaignConfig& config,
    const std::function<void(const CampaignProgress&)>& progress);

/// True when built with MPI and started under mpirun/srun (the launcher's environment).
bool campaign_mpi_launched();

/// MPI executor over all ranks (rank 0 owns the store and works too; the others serve);
/// only when campaign_mpi_launched() (else, or built without MPI, a local executor). `rank`
/// is set to this process's rank; ranks other than 0 get nullptr and must call
/// serve_campaign_tasks instead of using the store. Destroying the executor stops the
/// workers and finalises MPI.
std::unique_ptr<CampaignExecutor> make_mpi_executor(const CampaignConfig& config, int& rank);

/// A worker rank's loop: runs tasks from rank 0 until told to stop; then finalises MPI.
void serve_campaign_tasks(const CampaignConfig& config);

}  // namespace anascan::acquisition
