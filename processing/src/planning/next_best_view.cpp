// The next-best-view: of the candidate scanner poses, the one whose view observes the
// largest unobserved area (ties: the first, so the plan is reproducible). When even the best
// adds less than min_gain_fraction of the surface, what is left is either hidden from every
// pose on this side (turn the stone over) or nothing worth a scan (done).

#include <tbb/parallel_for.h>

#include "planning/steps.hpp"

namespace anascan {
namespace {

using planning_detail::Candidate;

struct Best {
    std::size_t index = 0;
    planning_detail::ViewScore score;
};

// The largest gain among the views that keep the overlap; when none does (early in a
// session, or a stone seen from one side only), the view with the most overlap that still
// adds something.
Best best_candidate(std::span<const Candidate> candidates,
                    const planning_detail::WantedSamples& wanted, const Eigen::Vector3d& up,
                    const NextViewConfig& config) {
    std::vector<planning_detail::ViewScore> scores(candidates.size());
    tbb::parallel_for(std::size_t{0}, candidates.size(), [&](std::size_t i) {
        scores[i] = planning_detail::score_view(candidates[i], wanted, up, config);
    });
    Best best, fallback;
    for (std::size_t i = 0; i < scores.size(); ++i) {
        const planning_detail::ViewScore& s = scores[i];
        if (s.overlap_fraction() >= config.min_overlap_fraction) {
            if (s.gain_m2 > best.score.gain_m2) best = {i, s};
        } else if (s.gain_m2 > 0.0 && s.overlap_fraction() > fallback.score.overlap_fraction()) {
            fallback = {i, s};
        }
    }
    return best.score.gain_m2 > 0.0 ? best : fallback;
}

Eigen::Vector3d mean_normal(const planning_detail::WantedSamples& wanted,
                            std::span<const std::size_t> seen) {
    Eigen::Vector3d n = Eigen::Vector3d::Zero();
    for (std::size_t i : seen) n += wanted.samples[i].normal;
    if (n.norm() > 0.0) n.normalize();
    return n;
}

void measure_reach(NextView& view, std::span<const Candidate> candidates,
                   const planning_detail::WantedSamples& wanted, const Eigen::Vector3d& up,
                   const NextViewConfig& config) {
    const std::vector<bool> reachable =
        planning_detail::observable_by_any(candidates, wanted, up, config);
    std::size_t reached = 0;
    for (bool r : reachable) reached += r ? 1 : 0;
    view.visible_now_area_m2 = wanted.area_per_sample_m2 * static_cast<double>(reached);
    view.after_turn_area_m2 = wanted.total_area_m2 - view.visible_now_area_m2;
}

}  // namespace

NextView plan_next_view(const CoverageReport& coverage, const NextViewConfig& config) {
    NextView view;
    if (coverage.status != CoverageStatus::kOk || coverage.surface_area_m2 <= 0.0) {
        view.hint = planning_detail::hint_text(view, Eigen::Vector3d::Zero());
        return view;
    }
    view.frame = planning_frame(coverage, config.up_hint_world);
    const Eigen::Vector3d up = view.frame.R_stone_world.row(2).transpose();
    const planning_detail::WantedSamples wanted =
        planning_detail::wanted_samples(coverage, config.max_samples);
    const std::vector<Candidate> candidates =
        planning_detail::candidate_views(coverage, wanted, view.frame, config);
    view.candidates = candidates.size();
    measure_reach(view, candidates, wanted, up, config);
    const Best best = best_candidate(candidates, wanted, up, config);
    view.gain_area_m2 = best.score.gain_m2;
    view.overlap_fraction = best.score.overlap_fraction();
    view.gain_fraction = view.gain_area_m2 / coverage.surface_area_m2;
    Eigen::Vector3d aimed_normal = Eigen::Vector3d::Zero();
    if (view.gain_fraction >= config.min_gain_fraction) {
        const Candidate& c = candidates[best.index];
        view.advice = NextViewAdvice::kScan;
        view.sensor_world_m = c.sensor_m, view.aim_world_m = c.aim_m;
        view.standoff_m = c.standoff_m, view.height_m = c.height_m;
        aimed_normal = mean_normal(wanted, planning_detail::observed_by(c, wanted, up, config));
    } else {
        const double min_area = config.min_gain_fraction * coverage.surface_area_m2;
        view.advice =
            view.after_turn_area_m2 >= min_area ? NextViewAdvice::kTurnOver : NextViewAdvice::kDone;
    }
    view.hint = planning_detail::hint_text(view, aimed_normal);
    return view;
}

}  // namespace anascan
