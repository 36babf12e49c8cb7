// The registration worker of a capture session: places each saved scan live, then, when
// it has caught up, refines the poses in the background and recomputes the coverage.
#include <malloc.h>
#include <spdlog/spdlog.h>

#include <cstdio>

#include "anascan/acquisition/coverage/session_coverage.hpp"
#include "anascan/processing/core/stopwatch.hpp"
#include "capture/impl.hpp"
#include "live/json.hpp"

namespace anascan::acquisition {
namespace {

/// "2.31 s after saving" for a new scan; a scan of a reopened session, or one the operator
/// asked to register again, has no new latency.
std::string when(std::optional<double> latency_s) {
    if (!latency_s) return "registered again";
    char text[48];
    std::snprintf(text, sizeof(text), "%.2f s after saving", *latency_s);
    return text;
}

std::string decision_message(const LiveDecision& decision, std::optional<double> latency_s) {
    char text[512];
    if (decision.registered &&
        (decision.method == LiveMethod::kFirst || decision.method == LiveMethod::kNewGroup))
        std::snprintf(text, sizeof(text), "registered scan %lld: opens group %d (%s), %s",
                      static_cast<long long>(decision.seq), decision.group,
                      decision.method == LiveMethod::kFirst ? "the session's frame"
                                                            : "matches no earlier scan yet",
                      when(latency_s).c_str());
    else if (decision.registered)
        std::snprintf(text, sizeof(text),
                      "registered scan %lld: group %d by %s, RMS %.3f mm, overlap %.0f %%, %s",
                      static_cast<long long>(decision.seq), decision.group,
                      to_string(decision.method).data(), decision.rms_m * 1e3,
                      decision.overlap_fraction * 100.0, when(latency_s).c_str());
    else
        std::snprintf(text, sizeof(text),
                      "scan %lld NOT registered: %s — check that the stone is in view and "
                      "overlaps earlier scans; exclude it or scan this side again",
                      static_cast<long long>(decision.seq), decision.message.c_str());
    return text;
}

/// The registrar's memory by part and the C heap's (glibc: in use, and held from the system),
/// on the debug log: where a session's memory goes per scan.
void log_memory(const LiveRegistrar& registrar, const std::string& when) {
    if (!spdlog::should_log(spdlog::level::debug)) return;
    const LiveMemoryReport m = registrar.memory();
    const struct mallinfo2 heap = mallinfo2();
    constexpr double kMb = 1e-6;
    spdlog::debug(
        "memory {}: registrar {:.1f} MB for {} scans (clouds {:.1f}, trees {:.1f}, features "
        "{:.1f} of {}, {} links {:.1f}, model {:.1f}); heap in use {:.1f} MB, held {:.1f} MB",
        when, m.total_bytes() * kMb, m.scans, m.cloud_bytes * kMb, m.tree_bytes * kMb,
        m.feature_bytes * kMb, m.features_kept, m.links, m.link_bytes * kMb,
        m.model_cache_bytes * kMb, (heap.uordblks + heap.hblkhd) * kMb,
        (heap.arena + heap.hblkhd) * kMb);
}

}  // namespace

void CaptureSession::Impl::requeue_session_scans() {
    auto records = store->scans();
    if (!records) return;
    for (const ScanRecord& record : *records) {
        if (record.excluded) continue;
        begin_work();
        SavedScan saved{.seq = record.seq,
                        .turned_over = record.turned_over_before,
                        .acknowledged_at = record.acknowledged_at,
                        .resumed = true};
        saved.previous_latency_s = record.latency_s;
        to_register.push(std::move(saved));
    }
}

void CaptureSession::Impl::registration_loop() {
    // Background work (refinement, merges, coverage) runs whenever no scan waits, and
    // counts as work in flight until it has nothing left to do, so wait_until_idle sees
    // the final poses.
    bool background = false;
    int background_steps = 0;
    for (;;) {
        auto item =
            background ? to_register.pop_for(std::chrono::milliseconds(0)) : to_register.pop();
        if (item) {
            if (item->exclude_change != 0) {
                registrar.exclude(item->seq, item->exclude_change > 0);
            } else {
                register_one(*item);
                if (item->scan) --registration_items_with_points;
                if (item->resumed && !item->reregister) settle_after_replayed_scan();
                const std::int64_t seq = item->seq;
                item.reset();    // The full scan, unless the store still holds it.
                malloc_trim(0);  // It and the preparation's temporaries go back to the system.
                log_memory(registrar, "after scan " + std::to_string(seq));
            }
            refine_due = coverage_due = true;
            if (!background) begin_work();
            background = true;
            background_steps = 0;
            end_work();
            continue;
        }
        if (!background) break;  // closed and drained
        const bool more =
            ++background_steps < config.max_background_steps && refine_in_background();
        if (!more) {
            // The round's temporaries (merged models, correspondences) are freed: give the
            // free pages back, so the process keeps what the scans keep (glibc keeps freed
            // memory in its per-thread arenas otherwise: 140 MB held over 250 MB in use
            // after 20 scans).
            malloc_trim(0);
            log_memory(registrar, "after refining");
            update_coverage();
            background = false;
            end_work();
        }
    }
}

void CaptureSession::Impl::register_one(const SavedScan& saved) {
    std::shared_ptr<const Scan> scan = saved.scan;
    if (!scan) {
        auto loaded = store->load_scan(saved.seq);
        if (!loaded) {
            const std::string message = "cannot register: " + loaded.error().message;
            (void)store->record_registration(
                saved.seq, {.state = ScanState::kFailed, .quality_json = reason_json(message)});
            emit({.kind = SessionEventKind::kRegistrationFailed,
                  .seq = saved.seq,
                  .message = message});
            return;
        }
        scan = std::make_shared<const Scan>(std::move(*loaded));
    }
    if (config.coverage_live)
        coverage_copies[saved.seq] = make_coverage_copy(*scan, config.coverage_voxel_size_m);
    LiveScanInput input{.seq = saved.seq,
                        .cloud = scan->cloud,
                        .sensor_origin_scan_m = scan->meta.sensor_origin_scan_m,
                        .turned_over_before = saved.turned_over};
    record_decision(saved, saved.reregister ? registrar.reregister(std::move(input))
                                            : registrar.add(std::move(input)));
}

void CaptureSession::Impl::record_decision(const SavedScan& saved, const LiveDecision& decision) {
    const std::optional<double> live_latency_s =
        saved.resumed ? std::nullopt : std::optional<double>(seconds_since(saved.acknowledged_at));
    const double latency_s = live_latency_s.value_or(0.0);
    const std::optional<double> recorded_latency =
        saved.resumed ? saved.previous_latency_s : std::optional<double>(latency_s);
    RegistrationUpdate update{
        .state = decision.registered ? ScanState::kRegistered : ScanState::kFailed,
        .group = decision.registered ? decision.group : -1,
        .quality_json = decision_json(decision),
        .latency_s = decision.registered ? recorded_latency : std::nullopt};
    if (decision.registered) update.pose = decision.T_group_scan;
    if (auto ok = store->record_registration(saved.seq, update); !ok)
        emit({.kind = SessionEventKind::kSaveFailed,
              .seq = saved.seq,
              .message = ok.error().message});
    if (!decision.registered)
        (void)store->add_event("registration-failed", "",
                               decision_message(decision, live_latency_s));
    emit({.kind = decision.registered ? SessionEventKind::kRegistered
                                      : SessionEventKind::kRegistrationFailed,
          .seq = saved.seq,
          .message = decision_message(decision, live_latency_s),
          .group = decision.group,
          .method = std::string(to_string(decision.method)),
          .rms_m = decision.rms_m,
          .overlap_fraction = decision.overlap_fraction,
          .latency_s = latency_s});
    refine_due = coverage_due = true;
}

void CaptureSession::Impl::settle_after_replayed_scan() {
    for (int step = 0; step < config.max_background_steps && refine_in_background(false); ++step) {
    }
}

bool CaptureSession::Impl::refine_in_background(bool interruptible) {
    if (!refine_due) return false;
    // A scan waiting to be registered interrupts the round (it goes on after that scan).
    const std::vector<PoseUpdate> updates =
        registrar.refine([this, interruptible] { return interruptible && to_register.size() > 0; });
    const LiveRefineReport& report = registrar.last_refine_report();
    // refine() works to a budget per call: call again while it still finds work.
    const bool more = !updates.empty() || report.new_links > 0 || report.merges > 0 ||
                      report.merge_attempts > 0 || report.interrupted ||
                      !report.taken_out.empty() || !report.split_off.empty();
    refine_due = more;
    record_taken_out(report.taken_out);
    for (const LiveTakenOut& t : report.split_off)
        (void)store->add_event("registration-split", "",
                               "scan " + std::to_string(t.seq) + " leaves group " +
                                   std::to_string(t.group) + ": " + t.reason);
    if (updates.empty()) return more;
    std::vector<std::pair<std::int64_t, PoseInGroup>> poses;
    poses.reserve(updates.size());
    for (const PoseUpdate& u : updates)
        poses.push_back({u.seq, {.group = u.group, .T_group_scan = u.T_group_scan}});
    if (auto ok = store->update_poses(poses); !ok) {
        emit({.kind = SessionEventKind::kSaveFailed, .message = ok.error().message});
        return more;
    }
    char message[160];
    std::snprintf(message, sizeof(message),
                  "refined: %zu poses updated (%zu new links, %zu merges)", updates.size(),
                  report.new_links, report.merges);
    emit({.kind = SessionEventKind::kPosesRefined, .message = message, .count = updates.size()});
    return more;
}

void CaptureSession::Impl::record_taken_out(const std::vector<LiveTakenOut>& taken_out) {
    for (const LiveTakenOut& t : taken_out) {
        const std::string message = "scan " + std::to_string(t.seq) +
                                    " FLAGGED and taken out of group " + std::to_string(t.group) +
                                    ": " + t.reason +
                                    "; scan that part again, or register it again";
        if (auto ok = store->record_registration(
                t.seq, {.state = ScanState::kFlagged, .quality_json = taken_out_json(t, message)});
            !ok)
            emit({.kind = SessionEventKind::kSaveFailed,
                  .seq = t.seq,
                  .message = ok.error().message});
        (void)store->add_event("registration-flagged", "", message);
        emit({.kind = SessionEventKind::kRegistrationFlagged,
              .seq = t.seq,
              .message = message,
              .group = t.group});
    }
}

void CaptureSession::Impl::update_coverage() {
    if (!config.coverage_live || !coverage_due) return;
    coverage_due = false;
    // Coverage sees the whole scans (it removes the ground itself), reduced as
    // session_coverage reduces them, placed by the registrar's current poses.
    // The largest group, by the rule session_coverage and the field app use.
    const std::vector<LiveModelScan> model = registrar.model();
    std::vector<int> member_groups;
    for (const LiveModelScan& m : model) member_groups.push_back(m.group);
    const int group = largest_group_id(member_groups);
    std::vector<CoverageScanView> views;
    for (const LiveModelScan& m : model) {
        const auto copy = coverage_copies.find(m.seq);
        if (m.group != group || copy == coverage_copies.end()) continue;
        views.push_back({.cloud = &copy->second.cloud,
                         .T_world_scan = m.T_group_scan,
                         .sensor_origin_scan_m = copy->second.sensor_origin_scan_m,
                         .points_per_point = copy->second.points_per_point});
    }
    if (views.empty()) return;
    const CoverageReport report = compute_coverage(views, config.coverage);
    (void)store->set_value("coverage", coverage_to_json(report));
    char message[200];
    std::snprintf(message, sizeof(message),
                  "coverage %.1f %% of the %.3f m² surface estimated so far from %zu scans "
                  "(the estimate grows until every side is seen), %zu holes",
                  report.fraction * 100.0, report.surface_area_m2, views.size(),
                  report.holes.size());
    emit({.kind = SessionEventKind::kCoverage,
          .message = message,
          .coverage_fraction = report.fraction,
          .count = report.holes.size()});
}

}  // namespace anascan::acquisition
