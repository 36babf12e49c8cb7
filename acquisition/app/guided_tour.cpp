#include "guided_tour.hpp"

#include <spdlog/spdlog.h>

#include <cstdio>

#include "anascan/acquisition/coverage/session_coverage.hpp"

namespace anascan::cli {
namespace {

constexpr int kTurnedSideWalk = 6;  // Fixed views around the turned side until it joins.

// Whether the model (the largest group) holds a scan taken after scan `last_before_turn`.
bool turned_side_joined(const acquisition::SessionStore& store, std::int64_t last_before_turn) {
    auto scans = store.scans();
    if (!scans) return false;
    const int group = acquisition::largest_group(*scans);
    for (const acquisition::ScanRecord& s : *scans)
        if (s.seq > last_before_turn && acquisition::counts_in_group(s) && s.group == group)
            return true;
    return false;
}

std::int64_t scan_count(const acquisition::SessionStore& store) {
    auto scans = store.scans();
    return scans ? static_cast<std::int64_t>(scans->size()) : 0;
}

}  // namespace

std::optional<acquisition::CaptureRequest> GuidedOperator::after_turn() {
    if (turned_side_views_ >= kTurnedSideWalk) return std::nullopt;
    return scanner_sources::turned_side_request(tour_, turned_side_views_++, kTurnedSideWalk);
}

std::optional<acquisition::CaptureRequest> GuidedOperator::next(
    acquisition::CaptureSession& session, int index) {
    if (index == 0) return scanner_sources::tour_request(tour_, 0);
    session.wait_until_idle();
    auto plan = acquisition::session_next_view(session.store(), {}, {});
    if (!plan) {
        spdlog::warn("guided tour: no plan ({}); walking on", plan.error().message);
        return turned_ ? after_turn() : scanner_sources::tour_request(tour_, index);
    }
    plan_times_s_.push_back(plan->plan_s);
    std::printf("coverage %.1f %%; next: %s\n", 100.0 * plan->coverage.fraction,
                plan->view.hint.c_str());
    if (plan->coverage.fraction >= target_fraction_) return std::nullopt;
    const bool plan_fits_the_stone =
        !turned_ || turned_side_joined(session.store(), last_before_turn_);
    if (plan->view.advice == NextViewAdvice::kScan && plan_fits_the_stone) {
        auto to_truth = acquisition::group_to_truth(session.store());
        if (to_truth && *to_truth) {
            const Pose& T = **to_truth;
            return scanner_sources::guided_request(tour_,
                                                   {.sensor_m = T * plan->view.sensor_world_m,
                                                    .aim_m = T * plan->view.aim_world_m,
                                                    .turned = turned_});
        }
        spdlog::warn("guided tour: no registered scan with a true pose to walk by");
    }
    if (plan->view.advice == NextViewAdvice::kTurnOver && !turned_) {
        turned_ = true;
        last_before_turn_ = scan_count(session.store());
        std::printf("the stone is turned over before view %d\n", index + 1);
        return after_turn();
    }
    // Turned, but the turned side has not joined the model yet: walk around it.
    return turned_ ? after_turn() : std::nullopt;
}

}  // namespace anascan::cli
