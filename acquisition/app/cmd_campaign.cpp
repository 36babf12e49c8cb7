// anascan campaign init|register|status|export: a campaign of many unordered, unlabelled
// scans of many stones (docs/campaigns.md).
#include <spdlog/spdlog.h>
#include <tbb/global_control.h>

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <set>
#include <thread>

#include "anascan/acquisition/campaign/campaign_job.hpp"
#include "campaign_cli.hpp"
#include "commands.hpp"

namespace anascan::cli {
namespace {

namespace fs = std::filesystem;
using acquisition::CampaignStore;

struct InitOptions {
    std::string dir;
    std::vector<std::string> scans;
    std::string list;
    std::size_t candidates_per_scan = CampaignConfig{}.candidates_per_scan;
};

std::vector<std::string> listed_files(const std::string& list) {
    std::ifstream in(list);
    if (!in) throw CommandFailed(list + ": cannot read the scan list");
    std::vector<std::string> files;
    for (std::string line; std::getline(in, line);) {
        if (line.empty() || line[0] == '#') continue;
        const fs::path p(line);
        files.push_back(p.is_absolute() ? line : (fs::path(list).parent_path() / p).string());
    }
    return files;
}

/// Absolute paths, each once; a missing file is an error naming it, a repeat a warning.
std::vector<std::string> campaign_files(const InitOptions& o) {
    std::vector<std::string> given = o.scans;
    if (!o.list.empty()) {
        const std::vector<std::string> listed = listed_files(o.list);
        given.insert(given.end(), listed.begin(), listed.end());
    }
    std::vector<std::string> files;
    std::set<std::string> seen;
    for (const std::string& f : given) {
        std::error_code ec;
        if (!fs::is_regular_file(f, ec)) throw CommandFailed(f + ": no such scan file");
        const std::string path = fs::weakly_canonical(fs::absolute(f), ec).string();
        if (!seen.insert(path).second) {
            spdlog::warn("{}: listed more than once; recorded once", f);
            continue;
        }
        files.push_back(path);
    }
    if (files.empty()) throw CommandFailed("no scans given (SCAN... or --list FILE)");
    return files;
}

void run_init(const InitOptions& o) {
    const std::vector<std::string> files = campaign_files(o);
    auto store = CampaignStore::create(o.dir, files);
    if (!store) fail_command(store.error());
    const nlohmann::json config = {{"candidates_per_scan", o.candidates_per_scan}};
    if (auto ok = (*store)->set_value("config", config.dump()); !ok) fail_command(ok.error());
    std::printf("campaign %s: %zu scans\n", o.dir.c_str(), files.size());
}

void print_progress(const acquisition::CampaignProgress& p) {
    using Clock = std::chrono::steady_clock;
    static Clock::time_point last{};  // Throttle: at most one line a second per stage.
    const bool end = p.done == p.total;
    if (!end && Clock::now() - last < std::chrono::seconds(1)) return;
    last = Clock::now();
    spdlog::info("{}: {} of {} done ({} before this run), {:.2f} tasks/s, ETA {:.0f} s", p.stage,
                 p.done, p.total, p.done_before, p.rate_per_s, end ? 0.0 : p.eta_s);
}

void print_report(const acquisition::CampaignJobReport& report, int ranks) {
    for (const auto& s : report.stages) {
        std::printf("stage %s: %zu already done, %zu run now\n", s.stage.c_str(), s.already_done,
                    s.run_now);
    }
    std::printf("ranks: %d\n", ranks);
}

// Ranks started on this machine by the launcher (OpenMPI, then Slurm), 1 without one.
int ranks_on_this_node() {
    for (const char* name : {"OMPI_COMM_WORLD_LOCAL_SIZE", "SLURM_NTASKS_PER_NODE"}) {
        if (const char* v = std::getenv(name)) return std::max(1, std::atoi(v));
    }
    return 1;
}

// Each rank's share of the cores: a task's own loops (TBB) would otherwise start a worker
// per core in every rank, and idle workers spin on cores the other ranks need (two ranks
// on 2 cores took 136 s of processor time for the 98 s of one process).
std::size_t threads_per_process(int requested) {
    if (requested > 0) return std::size_t(requested);
    const int cores = std::max(1, int(std::thread::hardware_concurrency()));
    return std::size_t(std::max(1, cores / ranks_on_this_node()));
}

void run_register(const std::string& dir, int threads) {
    const tbb::global_control thread_limit(tbb::global_control::max_allowed_parallelism,
                                           threads_per_process(threads));
    const CampaignConfig defaults;
    std::unique_ptr<acquisition::CampaignExecutor> executor;
    int rank = 0;
    if (acquisition::campaign_mpi_launched()) {
        executor = acquisition::make_mpi_executor(defaults, rank);
        if (rank != 0) {
            acquisition::serve_campaign_tasks(defaults);
            return;
        }
    }
    auto store = CampaignStore::open(dir, false);
    if (!store) fail_command(store.error());
    const CampaignConfig config = stored_config(**store);
    if (executor == nullptr) executor = acquisition::make_local_executor(config);
    auto report = acquisition::run_campaign(**store, *executor, config, print_progress);
    if (!report) fail_command(report.error());
    print_report(*report, executor->ranks());
    print_status(**store);
}

}  // namespace

void add_campaign_command(CLI::App& app) {
    auto* campaign = app.add_subcommand(
        "campaign",
        "A campaign of many unordered, unlabelled scans of many stones: prepare and describe "
        "every scan, register only candidate pairs, find the stones and their poses");
    campaign->require_subcommand(1);
    auto init = std::make_shared<InitOptions>();
    auto* cmd = campaign->add_subcommand("init", "Create a campaign folder from scan files");
    cmd->add_option("dir", init->dir, "New campaign folder")->required();
    cmd->add_option("scans", init->scans, "Scans (.ply, plain points in any frame)");
    cmd->add_option("--list", init->list, "A text file naming one scan a line")
        ->check(CLI::ExistingFile);
    cmd->add_option("--candidates-per-scan", init->candidates_per_scan,
                    "Scans each scan proposes for registration (default 8)");
    cmd->callback([init] { run_init(*init); });
    auto dir = std::make_shared<std::string>();
    auto* reg = campaign->add_subcommand(
        "register",
        "Run (or resume) the campaign's stages; under mpirun/srun rank 0 owns the store and "
        "hands out tasks");
    reg->add_option("dir", *dir, "Campaign folder")->required();
    auto threads = std::make_shared<int>(0);
    reg->add_option("--threads", *threads,
                    "Worker threads of this process (default: all cores; under mpirun the "
                    "cores divided by the ranks on this machine)")
        ->check(CLI::NonNegativeNumber);
    reg->callback([dir, threads] { run_register(*dir, *threads); });
    add_campaign_status_commands(*campaign);
    add_campaign_eval_command(*campaign);
}

}  // namespace anascan::cli
