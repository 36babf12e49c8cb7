#include "capture_summary.hpp"

#include <spdlog/spdlog.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <map>
#include <memory>
#include <mutex>
#include <nlohmann/json.hpp>
#include <set>

#include "anascan/acquisition/coverage/session_coverage.hpp"
#include "anascan/acquisition/store/session_truth.hpp"

namespace anascan::cli {
namespace {

/// Nearest-rank percentile of sorted values.
double percentile(const std::vector<double>& sorted, double p) {
    if (sorted.empty()) return 0.0;
    const std::size_t rank = static_cast<std::size_t>(std::ceil(p / 100.0 * sorted.size()));
    return sorted[std::clamp<std::size_t>(rank, 1, sorted.size()) - 1];
}

}  // namespace

/// Prints the session's events, one line each, as they arrive: progress on stdout (a log a
/// script can follow: "saved scan N"), failures once, as errors on stderr.
acquisition::SessionEventSink printing_sink() {
    auto mutex = std::make_shared<std::mutex>();
    return [mutex](const acquisition::SessionEvent& event) {
        std::lock_guard lock(*mutex);
        using K = acquisition::SessionEventKind;
        if (event.kind == K::kDeviceError || event.kind == K::kSaveFailed ||
            event.kind == K::kRegistrationFailed || event.kind == K::kRegistrationFlagged) {
            spdlog::error("{}", event.message);
            return;
        }
        if (event.kind == K::kDeviceWarning) {
            spdlog::warn("{}", event.message);
            return;
        }
        std::printf("%s\n", event.message.c_str());
        std::fflush(stdout);
    };
}

/// The coverage of the finished session, from the scans on disk as `anascan coverage`
/// computes it, so that both report the same figure.
void store_final_coverage(acquisition::SessionStore& store) {
    auto report = acquisition::session_coverage(store, {});
    if (!report) {
        spdlog::warn("no coverage: {}", report.error().message);
        return;
    }
    if (auto ok = store.set_value("coverage", coverage_to_json(*report)); !ok)
        spdlog::warn("coverage not stored: {}", ok.error().message);
}

void print_capture_summary(const acquisition::SessionStore& store) {
    auto scans = store.scans();
    if (!scans) {
        std::printf("cannot read the session's scans: %s\n", scans.error().message.c_str());
        return;
    }
    std::map<std::string, int> by_state;
    std::set<int> groups;
    std::vector<double> latencies;
    for (const acquisition::ScanRecord& s : *scans) {
        ++by_state[std::string(acquisition::to_string(s.state))];
        if (s.state == acquisition::ScanState::kRegistered) groups.insert(s.group);
        if (s.latency_s) latencies.push_back(*s.latency_s);
    }
    std::sort(latencies.begin(), latencies.end());
    std::printf("session %s: %zu scans:", store.dir().c_str(), scans->size());
    for (const auto& [state, count] : by_state) std::printf(" %d %s", count, state.c_str());
    std::printf("; %zu groups\n", groups.size());
    if (!latencies.empty())
        std::printf(
            "latency, saved to registered: median %.2f s, 95th percentile %.2f s (%zu scans)\n",
            percentile(latencies, 50), percentile(latencies, 95), latencies.size());
    auto truth = acquisition::evaluate_session_truth(store);
    if (truth && *truth)
        std::printf(
            "against the simulated truth: %zu of %zu scans placed in the main group, worst "
            "rotation %.4f°, worst translation %.3f mm (at the scan centroids, frame of scan "
            "%s)\n",
            (*truth)->placed, (*truth)->scans.size(), (*truth)->max_rotation_deg,
            (*truth)->max_translation_m * 1e3, (*truth)->reference.c_str());
    if (truth && *truth)
        std::printf(
            "  in the best-fit frame of all placed scans: worst rotation %.4f°, worst "
            "translation %.3f mm\n",
            (*truth)->max_rotation_best_fit_deg, (*truth)->max_translation_best_fit_m * 1e3);
    auto coverage = store.value("coverage");
    if (coverage && *coverage) {
        const auto j = nlohmann::json::parse(**coverage, nullptr, false);
        if (j.is_object() && j.contains("fraction"))
            std::printf(
                "coverage at the end: %.1f %% of the %.3f m² surface estimated from all "
                "registered scans of the model, %zu holes (recomputed from the saved scans)\n",
                j["fraction"].get<double>() * 100.0, j.value("surface_area_m2", 0.0),
                j.value("hole_count", j.contains("holes") ? j["holes"].size() : std::size_t{0}));
    }
}

}  // namespace anascan::cli
