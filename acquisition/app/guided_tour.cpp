#include "guided_tour.hpp"

#include <spdlog/spdlog.h>

#include <algorithm>
#include <cstdio>
#include <string>

#include "anascan/acquisition/coverage/session_coverage.hpp"
#include "anascan/acquisition/store/groups.hpp"

namespace anascan::cli {
namespace {

constexpr int kTurnedSideWalk = 6;  // Fixed views around the turned side until it joins.

using Scans = std::vector<acquisition::ScanRecord>;

// Whether the model (the largest group) holds a scan taken after scan `last_before_turn`.
bool turned_side_joined(const Scans& scans, std::int64_t last_before_turn) {
    const int group = acquisition::largest_group(scans);
    for (const acquisition::ScanRecord& s : scans)
        if (s.seq > last_before_turn && acquisition::counts_in_group(s) && s.group == group)
            return true;
    return false;
}

std::int64_t last_seq(const std::vector<acquisition::ScanRecord>& scans) {
    std::int64_t last = 0;
    for (const acquisition::ScanRecord& s : scans) last = std::max(last, s.seq);
    return last;
}

}  // namespace

void GuidedOperator::note_whether_the_asked_view_joined(const Scans& scans) {
    if (!asked_) return;
    const AskedView asked = *asked_;
    asked_.reset();
    const int group = acquisition::largest_group(scans);
    for (const acquisition::ScanRecord& s : scans) {
        if (s.seq != asked.seq) continue;
        if (acquisition::counts_in_group(s) && s.group == group) return;
        failed_.push_back(asked);
        std::printf(
            "guided tour: scan %lld, from the view asked for, is not in the model (%s); that "
            "view is not asked for again\n",
            static_cast<long long>(s.seq), std::string(acquisition::to_string(s.state)).c_str());
        return;
    }
}

std::vector<Eigen::Vector3d> GuidedOperator::failed_views(const Scans& scans) const {
    // Positions are in the frame of the group that was the model when they were asked for.
    const int group = acquisition::largest_group(scans);
    std::vector<Eigen::Vector3d> out;
    for (const AskedView& v : failed_)
        if (v.group == group) out.push_back(v.sensor_model_m);
    return out;
}

std::optional<acquisition::CaptureRequest> GuidedOperator::after_turn() {
    if (turned_side_views_ >= kTurnedSideWalk) return std::nullopt;
    return scanner_sources::turned_side_request(tour_, turned_side_views_++, kTurnedSideWalk);
}

std::optional<acquisition::CaptureRequest> GuidedOperator::next(
    acquisition::CaptureSession& session, int index) {
    if (index == 0) return scanner_sources::tour_request(tour_, 0);
    session.wait_until_idle();
    // The scans as the plan sees them, read once (the session is idle until the next view).
    auto read = session.store().scans();
    const Scans scans = read ? std::move(*read) : Scans{};
    note_whether_the_asked_view_joined(scans);
    NextViewConfig config;
    config.failed_sensor_positions_world = failed_views(scans);
    auto plan = acquisition::session_next_view(session.store(), {}, config);
    if (!plan) {
        spdlog::warn("guided tour: no plan ({}); walking on", plan.error().message);
        return turned_ ? after_turn() : scanner_sources::tour_request(tour_, index);
    }
    plan_times_s_.push_back(plan->plan_s);
    std::printf("coverage %.1f %%; next: %s\n", 100.0 * plan->coverage.fraction,
                plan->view.hint.c_str());
    if (plan->coverage.fraction >= target_fraction_) return std::nullopt;
    const bool plan_fits_the_stone = !turned_ || turned_side_joined(scans, last_before_turn_);
    if (plan->view.advice == NextViewAdvice::kScan && plan_fits_the_stone) {
        auto to_truth = acquisition::group_to_truth(session.store());
        if (to_truth && *to_truth) {
            const Pose& T = **to_truth;
            asked_ = AskedView{.sensor_model_m = plan->view.sensor_world_m,
                               .group = acquisition::largest_group(scans),
                               .seq = last_seq(scans) + 1};
            return scanner_sources::guided_request(tour_,
                                                   {.sensor_m = T * plan->view.sensor_world_m,
                                                    .aim_m = T * plan->view.aim_world_m,
                                                    .turned = turned_});
        }
        spdlog::warn("guided tour: no registered scan with a true pose to walk by");
    }
    if (plan->view.advice == NextViewAdvice::kTurnOver && !turned_) {
        turned_ = true;
        last_before_turn_ = static_cast<std::int64_t>(scans.size());
        std::printf("the stone is turned over before view %d\n", index + 1);
        return after_turn();
    }
    // Turned, but the turned side has not joined the model yet: walk around it.
    return turned_ ? after_turn() : std::nullopt;
}

}  // namespace anascan::cli
