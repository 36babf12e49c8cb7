// The MPI executor: rank 0 owns the store and hands out tasks, largest first, keeping two
// queued at every worker so that none waits for rank 0; between results rank 0 runs the
// smallest tasks itself. Workers load only the files a task names and return its result.
#include <mpi.h>

#include <algorithm>
#include <chrono>
#include <cstdlib>
#include <cstring>
#include <deque>
#include <thread>

#include "anascan/acquisition/campaign/campaign_job.hpp"

namespace anascan::acquisition {
namespace {

constexpr int kTagTask = 1, kTagResult = 2, kTagStop = 3;
constexpr int kQueuedPerWorker = 2;

using Bytes = std::vector<char>;

void put(Bytes& out, const void* data, std::size_t bytes) {
    const auto* p = static_cast<const char*>(data);
    out.insert(out.end(), p, p + bytes);
}

template <class T>
T take(const Bytes& in, std::size_t& at) {
    T v{};
    if (at + sizeof(T) <= in.size()) std::memcpy(&v, in.data() + at, sizeof(T));
    at += sizeof(T);
    return v;
}

Bytes pack(const CampaignTask& t) {
    Bytes out;
    const auto kind = static_cast<int>(t.kind);
    put(out, &kind, sizeof kind);
    put(out, &t.id, sizeof t.id);
    put(out, t.input_json.data(), t.input_json.size());
    return out;
}

CampaignTask unpack_task(const Bytes& in) {
    std::size_t at = 0;
    CampaignTask t;
    t.kind = static_cast<CampaignTaskKind>(take<int>(in, at));
    t.id = take<std::int64_t>(in, at);
    t.input_json.assign(in.begin() + static_cast<std::ptrdiff_t>(std::min(at, in.size())),
                        in.end());
    return t;
}

Bytes pack(const CampaignTaskResult& r) {
    Bytes out;
    const auto kind = static_cast<int>(r.kind);
    const std::uint64_t json_bytes = r.output_json.size();
    put(out, &kind, sizeof kind);
    put(out, &r.id, sizeof r.id);
    put(out, &json_bytes, sizeof json_bytes);
    put(out, r.output_json.data(), r.output_json.size());
    put(out, r.blob.data(), r.blob.size());
    return out;
}

CampaignTaskResult unpack_result(const Bytes& in) {
    std::size_t at = 0;
    CampaignTaskResult r;
    r.kind = static_cast<CampaignTaskKind>(take<int>(in, at));
    r.id = take<std::int64_t>(in, at);
    const auto json_bytes = static_cast<std::size_t>(take<std::uint64_t>(in, at));
    const std::size_t end = std::min(in.size(), at + json_bytes);
    r.output_json.assign(in.data() + std::min(at, in.size()), in.data() + end);
    r.blob.assign(in.begin() + static_cast<std::ptrdiff_t>(end), in.end());
    return r;
}

/// Receives the message `status` announced.
Bytes receive(const MPI_Status& probed) {
    int count = 0;
    MPI_Get_count(&probed, MPI_CHAR, &count);
    Bytes bytes(static_cast<std::size_t>(count));
    MPI_Recv(bytes.data(), count, MPI_CHAR, probed.MPI_SOURCE, probed.MPI_TAG, MPI_COMM_WORLD,
             MPI_STATUS_IGNORE);
    return bytes;
}

// A blocking MPI_Probe spins in OpenMPI: a worker waiting for its next task (or rank 0 for
// a result) would take a core from the rank that is computing. Polling with short sleeps
// leaves it free; a task runs for tenths of a second, so the millisecond of latency is lost.
void wait_for_message(int source, int tag, MPI_Status& status) {
    auto pause = std::chrono::microseconds(50);
    for (;;) {
        int ready = 0;
        MPI_Iprobe(source, tag, MPI_COMM_WORLD, &ready, &status);
        if (ready) return;
        std::this_thread::sleep_for(pause);
        pause = std::min(pause * 2, std::chrono::microseconds(2000));
    }
}

void send(const Bytes& bytes, int rank, int tag) {
    MPI_Send(bytes.data(), static_cast<int>(bytes.size()), MPI_CHAR, rank, tag, MPI_COMM_WORLD);
}

class MpiExecutor : public CampaignExecutor {
public:
    MpiExecutor(const CampaignConfig& config, int size) : config_(config), size_(size) {}
    ~MpiExecutor() override {
        for (int w = 1; w < size_; ++w) send({}, w, kTagStop);
        MPI_Finalize();
    }
    int ranks() const override { return size_; }

    Expected<void> run(std::vector<CampaignTask> tasks, const Sink& sink) override {
        std::stable_sort(tasks.begin(), tasks.end(),
                         [](const auto& a, const auto& b) { return a.cost > b.cost; });
        queue_.assign(tasks.begin(), tasks.end());
        outstanding_.assign(static_cast<std::size_t>(size_), 0);
        for (int w = 1; w < size_; ++w) refill(w);
        while (!queue_.empty() || busy() > 0) {
            if (auto ok = drain(sink, !queue_.empty()); !ok) return ok;
            if (queue_.empty()) continue;
            const CampaignTask task = queue_.back();  // Rank 0 takes the smallest.
            queue_.pop_back();
            if (auto ok = sink(run_campaign_task(task, config_)); !ok) return ok;
        }
        return {};
    }

private:
    int busy() const {
        int n = 0;
        for (int o : outstanding_) n += o;
        return n;
    }

    void refill(int w) {
        while (outstanding_[static_cast<std::size_t>(w)] < kQueuedPerWorker && !queue_.empty()) {
            send(pack(queue_.front()), w, kTagTask);
            queue_.pop_front();
            ++outstanding_[static_cast<std::size_t>(w)];
        }
    }

    /// Takes in the results that arrived (waits for one when `poll_only` is false and some
    /// are outstanding) and refills their workers.
    Expected<void> drain(const Sink& sink, bool poll_only) {
        for (;;) {
            MPI_Status status;
            int ready = 0;
            if (poll_only || busy() == 0) {
                MPI_Iprobe(MPI_ANY_SOURCE, kTagResult, MPI_COMM_WORLD, &ready, &status);
            } else {
                wait_for_message(MPI_ANY_SOURCE, kTagResult, status);
                ready = 1;
            }
            if (!ready) return {};
            const CampaignTaskResult result = unpack_result(receive(status));
            --outstanding_[static_cast<std::size_t>(status.MPI_SOURCE)];
            refill(status.MPI_SOURCE);
            if (auto ok = sink(result); !ok) return ok;
            poll_only = true;
        }
    }

    CampaignConfig config_;
    int size_ = 1;
    std::deque<CampaignTask> queue_;
    std::vector<int> outstanding_;
};

void init_mpi() {
    int initialised = 0;
    MPI_Initialized(&initialised);
    if (!initialised) MPI_Init(nullptr, nullptr);
}

}  // namespace

bool campaign_mpi_launched() {
    for (const char* name : {"OMPI_COMM_WORLD_SIZE", "PMI_SIZE", "PMIX_RANK"}) {
        if (std::getenv(name) != nullptr) return true;
    }
    return false;
}

std::unique_ptr<CampaignExecutor> make_mpi_executor(const CampaignConfig& config, int& rank) {
    init_mpi();
    int size = 1;
    MPI_Comm_rank(MPI_COMM_WORLD, &rank);
    MPI_Comm_size(MPI_COMM_WORLD, &size);
    if (rank != 0) return nullptr;
    return std::make_unique<MpiExecutor>(config, size);
}

void serve_campaign_tasks(const CampaignConfig& config) {
    for (;;) {
        MPI_Status status;
        wait_for_message(0, MPI_ANY_TAG, status);
        const Bytes bytes = receive(status);
        if (status.MPI_TAG != kTagTask) break;
        send(pack(run_campaign_task(unpack_task(bytes), config)), 0, kTagResult);
    }
    MPI_Finalize();
}

}  // namespace anascan::acquisition
