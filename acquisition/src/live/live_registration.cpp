// LiveRegistrar: add() as named steps (prepare → cheap hypotheses → global → new group).
#include "anascan/acquisition/live/live_registration.hpp"

#include <cstdio>
#include <string>
#include <utility>

#include "live/state.hpp"

namespace anascan::acquisition {
namespace {

using Clock = std::chrono::steady_clock;

void copy_figures(const FineRegistrationResult& fine, LiveDecision& decision) {
    decision.T_group_scan = fine.T_target_source;
    decision.rms_m = fine.rms_m;
    decision.overlap_fraction = fine.overlap_fraction;
    decision.normal_deviation_deg = fine.normal_deviation_deg.value_or(0.0);
    decision.degeneracy = fine.degeneracy.eigenvalue_ratio;
}

std::string summary(const LiveDecision& d) {
    char text[240];
    std::snprintf(text, sizeof(text),
                  "scan %lld: %s, group %d, rms %.3f mm, overlap %.1f %%, normals %.2f deg, "
                  "degeneracy %.4f, %zu attempts, %.3f s",
                  static_cast<long long>(d.seq), to_string(d.method).data(), d.group, d.rms_m * 1e3,
                  d.overlap_fraction * 100.0, d.normal_deviation_deg, d.degeneracy,
                  d.attempts.size(), d.time_s);
    return text;
}

}  // namespace

std::string_view to_string(LiveHypothesis hypothesis) {
    switch (hypothesis) {
        case LiveHypothesis::kMotionPrior:
            return "motion-prior";
        case LiveHypothesis::kMotionPrior2:
            return "motion-prior-2";
        case LiveHypothesis::kPreviousPose:
            return "previous-pose";
        case LiveHypothesis::kGlobal:
            return "global";
        case LiveHypothesis::kGlobalModel:
            return "global-model";
    }
    return "unknown";
}

std::string_view to_string(LiveMethod method) {
    switch (method) {
        case LiveMethod::kFirst:
            return "first";
        case LiveMethod::kMotionPrior:
            return "motion-prior";
        case LiveMethod::kPreviousPose:
            return "previous-pose";
        case LiveMethod::kGlobal:
            return "global";
        case LiveMethod::kNewGroup:
            return "new-group";
        case LiveMethod::kUnusable:
            return "unusable";
    }
    return "unknown";
}

LiveRegistrar::LiveRegistrar(LiveRegistrationConfig config) : state_(std::make_unique<State>()) {
    state_->config = std::move(config);
}

LiveRegistrar::~LiveRegistrar() = default;
LiveRegistrar::LiveRegistrar(LiveRegistrar&&) noexcept = default;
LiveRegistrar& LiveRegistrar::operator=(LiveRegistrar&&) noexcept = default;

LiveDecision LiveRegistrar::add(LiveScanInput scan) {
    if (state_->index_of_seq.contains(scan.seq)) {
        return {.seq = scan.seq,
                .method = LiveMethod::kUnusable,
                .message = "scan " + std::to_string(scan.seq) + " was already added"};
    }
    return state_->place(std::move(scan), true);
}

LiveDecision LiveRegistrar::reregister(LiveScanInput scan) {
    State& s = *state_;
    std::optional<int> side;  // An old scan stays on the side it was captured on.
    if (const auto it = s.index_of_seq.find(scan.seq); it != s.index_of_seq.end()) {
        // The old entry is retired (out of the model, the links and the refinement); the
        // scan comes back as a new entry.
        const std::size_t old = it->second;
        side = s.scans[old].side;
        s.scans[old] = {.seq = scan.seq, .excluded = true};
        std::erase_if(s.links,
                      [&](const live::Link& l) { return l.target == old || l.source == old; });
        const auto involves_old = [&](const auto& kv) {
            return kv.first.first == old || kv.first.second == old;
        };
        std::erase_if(s.link_tried, involves_old);
        std::erase_if(s.link_forecasts, involves_old);
        s.index_of_seq.erase(it);
    }
    scan.turned_over_before = false;
    return s.place(std::move(scan), false, side);
}

LiveDecision LiveRegistrar::State::place(LiveScanInput scan, bool newest, std::optional<int> side) {
    const Clock::time_point start = Clock::now();
    LiveDecision decision{.seq = scan.seq};
    const bool turned = scan.turned_over_before;
    const std::string scale_note = adopt_device_scale(scan.cloud);
    live::Prepared prepared = live::prepare_scan(std::move(scan), config);
    decision.reduced_points = prepared.entry.cloud.size();
    if (!prepared.problem.empty()) {
        decision.method = LiveMethod::kUnusable;
        decision.message = "scan " + std::to_string(decision.seq) + ": " + prepared.problem;
        decision.time_s = seconds_since(start);
        return decision;
    }
    if (turned) {
        awaiting_turn = true;
        ++turn_count;
    }
    prepared.entry.side = side.value_or(turn_count);
    const bool first = groups().empty();
    const std::size_t index = scans.size();
    index_of_seq[decision.seq] = index;
    scans.push_back(std::move(prepared.entry));
    int group = -1;
    const std::optional<live::Verified> accepted =
        first ? std::nullopt
              : hypothesise(index, {.newest = newest, .turned = turned}, group, decision);
    record(index, accepted, group, first, decision);
    if (newest) awaiting_turn = false;
    decision.time_s = seconds_since(start);
    decision.message = summary(decision) + scale_note;
    return decision;
}

std::string LiveRegistrar::State::adopt_device_scale(const PointCloud& cloud) {
    if (!config.lengths_from_device || device_scale) return {};
    const DeviceScale scale = measure_device_scale(cloud);
    if (scale.samples == 0) return {};
    device_scale = scale;
    const double voxel_before_m = config.prepare.voxel_size_m;
    config = lengths_for_device(config, scale);
    char note[200];
    std::snprintf(note, sizeof(note), "; device: spacing %.3f mm, noise %.3f mm%s",
                  scale.spacing_m * 1e3, scale.noise_m * 1e3,
                  config.prepare.voxel_size_m > voxel_before_m ? ", lengths raised to it" : "");
    std::string out = note;
    if (config.prepare.voxel_size_m > voxel_before_m) {
        std::snprintf(note, sizeof(note), " (voxel %.1f mm)", config.prepare.voxel_size_m * 1e3);
        out += note;
    }
    return out;
}

std::optional<live::Verified> LiveRegistrar::State::hypothesise(std::size_t index,
                                                                live::PlaceMode mode, int& group,
                                                                LiveDecision& decision) {
    // The operator's predictions belong to the newest scan; a scan registered again goes
    // straight to global registration.
    std::optional<live::Verified> accepted;
    if (mode.newest) accepted = try_cheap(scans[index], group, decision.method, decision);
    const bool opens_the_new_side =
        mode.turned && mode.newest && config.hypotheses.new_group_after_turn;
    if (!accepted && !opens_the_new_side) {
        accepted = try_global(index, group, decision);
        decision.method = LiveMethod::kGlobal;
    }
    return accepted;
}

void LiveRegistrar::State::record(std::size_t index, const std::optional<live::Verified>& accepted,
                                  int group, bool first, LiveDecision& decision) {
    live::ScanEntry& entry = scans[index];
    entry.registered = true;
    if (accepted) {
        copy_figures(accepted->fine, decision);
        decision.group = group;
        accepted_rms_m.push_back(decision.rms_m);
        accepted_normal_deviation.push_back(decision.normal_deviation_deg);
        // Placed on a model that holds an unchecked merge: it leaves if that merge does.
        if (auto it = unchecked_merges.find(group);
            it != unchecked_merges.end() && !it->second.empty())
            it->second.back().followers.push_back(index);
    } else {
        decision.method = first ? LiveMethod::kFirst : LiveMethod::kNewGroup;
        decision.group = next_group++;
    }
    entry.group = decision.group;
    entry.T_group_scan = decision.T_group_scan;
    decision.registered = true;
}

void LiveRegistrar::exclude(std::int64_t seq, bool excluded) {
    const auto it = state_->index_of_seq.find(seq);
    if (it != state_->index_of_seq.end()) state_->scans[it->second].excluded = excluded;
}

std::vector<LiveModelScan> LiveRegistrar::model() const {
    std::vector<LiveModelScan> out;
    for (const live::ScanEntry& e : state_->scans) {
        if (!live::active(e)) continue;
        out.push_back({.seq = e.seq,
                       .group = e.group,
                       .cloud = &e.cloud,
                       .T_group_scan = e.T_group_scan,
                       .sensor_origin_scan_m = e.sensor_origin_m});
    }
    return out;
}

std::optional<PoseUpdate> LiveRegistrar::pose(std::int64_t seq) const {
    const auto it = state_->index_of_seq.find(seq);
    if (it == state_->index_of_seq.end()) return std::nullopt;
    const live::ScanEntry& e = state_->scans[it->second];
    if (!e.registered || !e.flagged.empty()) return std::nullopt;
    return PoseUpdate{.seq = e.seq, .group = e.group, .T_group_scan = e.T_group_scan};
}

std::size_t LiveRegistrar::group_count() const { return state_->groups().size(); }

const LiveRefineReport& LiveRegistrar::last_refine_report() const { return state_->report; }

}  // namespace anascan::acquisition
