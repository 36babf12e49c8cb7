#include "anascan/processing/registration/multiview/multiview_refinement.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <optional>

#include "anascan/processing/core/median.hpp"
#include "registration/multiview/steps.hpp"

namespace anascan {

using multiview_detail::Parametrisation;

std::string_view to_string(MultiviewStatus status) {
    switch (status) {
        case MultiviewStatus::kConverged:
            return "converged";
        case MultiviewStatus::kMaxRounds:
            return "max_rounds";
        case MultiviewStatus::kDisconnected:
            return "disconnected";
        case MultiviewStatus::kUnderconstrained:
            return "underconstrained";
        case MultiviewStatus::kInvalidInput:
            return "invalid_input";
    }
    return "unknown";
}

namespace {

bool valid_input(std::span<const Pose> poses, std::span<const MultiviewLink> links,
                 const MultiviewRefinementConfig& config) {
    if (poses.empty() || config.fixed_scan_index >= poses.size()) return false;
    const bool poses_finite = std::all_of(poses.begin(), poses.end(),
                                          [](const Pose& T) { return T.matrix().allFinite(); });
    const bool links_valid = std::all_of(links.begin(), links.end(), [&](const MultiviewLink& l) {
        return l.target_index < poses.size() && l.source_index < poses.size() &&
               l.target_index != l.source_index;
    });
    return poses_finite && links_valid;
}

// Stopping predicate: every free scan's last step below both tolerances.
bool step_below_tolerance(std::pair<double, double> max_step,
                          const MultiviewRefinementConfig& config) {
    return max_step.first < config.rotation_tolerance_rad &&
           max_step.second < config.translation_tolerance_m;
}

// Whether a link's RMS is too large: the absolute bound, or the robust multiple of the
// median of the active links (never below the floor).
bool exceeds_bound(double rms_m, double median_m, const MultiviewRefinementConfig& config) {
    const double robust_bound_m =
        std::max(config.median_rms_factor * median_m, config.median_rule_floor_m);
    return rms_m > config.max_link_rms_m || rms_m > robust_bound_m;
}

// The regression step (paper §4.2.4): evaluates ε_mv of every active link at the current
// poses and drops the single worst link above the bound (one per round, so that a biased
// link that bent its neighbours does not take good links with it). Returns the dropped link.
std::optional<std::size_t> prune_worst_link(std::span<const MultiviewLink> links,
                                            std::span<const Pose> poses,
                                            const MultiviewRefinementConfig& config,
                                            const std::vector<bool>& connected,
                                            std::vector<bool>& active) {
    std::vector<double> rms(links.size(), 0.0);
    std::vector<double> active_rms;
    for (std::size_t l = 0; l < links.size(); ++l) {
        // Links inside a part cut off from the fixed scan were not solved: leave them.
        if (!active[l] || !connected[links[l].target_index]) continue;
        rms[l] = multiview_detail::link_rms_m(links[l], poses);
        active_rms.push_back(rms[l]);
    }
    const double median_m = upper_median(active_rms);
    std::optional<std::size_t> worst;
    for (std::size_t l = 0; l < links.size(); ++l) {
        if (!active[l] || !connected[links[l].target_index]) continue;
        if (!exceeds_bound(rms[l], median_m, config)) continue;
        if (!worst || rms[l] > rms[*worst]) worst = l;
    }
    if (worst) active[*worst] = false;
    return worst;
}

// Links with too few usable correspondences never take part; the others are active.
std::vector<bool> initial_links(std::span<const MultiviewLink> links, std::span<const Pose> poses,
                                const MultiviewRefinementConfig& config,
                                std::vector<MultiviewLinkReport>& reports) {
    std::vector<bool> active(links.size(), false);
    for (std::size_t l = 0; l < links.size(); ++l) {
        reports[l].correspondence_count = multiview_detail::usable_count(links[l]);
        reports[l].ignored = reports[l].correspondence_count < config.min_link_correspondences;
        reports[l].rms_before_m = multiview_detail::link_rms_m(links[l], poses);
        active[l] = !reports[l].ignored;
    }
    return active;
}

// Scans without a chain of active links to the fixed scan keep their input pose.
void restore_disconnected(std::span<const Pose> initial, const std::vector<bool>& connected,
                          MultiviewRefinementResult& result) {
    result.disconnected_scans.clear();
    for (std::size_t s = 0; s < initial.size(); ++s) {
        if (connected[s]) continue;
        result.T_world_scan[s] = initial[s];
        result.disconnected_scans.push_back(s);
    }
}

MultiviewStatus final_status(const MultiviewRefinementResult& result,
                             const MultiviewRefinementConfig& config) {
    if (result.pivot_ratio < config.degeneracy_threshold) return MultiviewStatus::kUnderconstrained;
    if (!result.disconnected_scans.empty()) return MultiviewStatus::kDisconnected;
    return result.converged ? MultiviewStatus::kConverged : MultiviewStatus::kMaxRounds;
}

// One round: connectivity, assembly of eq. 4, solve, helical move, regression step.
// Returns true when the stopping predicate holds (small step, nothing dropped).
bool run_round(std::span<const Pose> initial, std::span<const MultiviewLink> links,
               const MultiviewRefinementConfig& config, Parametrisation& param,
               std::vector<bool>& active, MultiviewRefinementResult& result) {
    const std::size_t fixed = config.fixed_scan_index;
    const std::vector<bool> connected =
        multiview_detail::connected_scans(initial.size(), fixed, links, active);
    restore_disconnected(initial, connected, result);
    multiview_detail::assign_blocks(param, connected, fixed);
    if (param.block_count == 0) {
        result.pivot_ratio = 1.0;
        return true;
    }
    const multiview_detail::BlockSystem system =
        multiview_detail::assemble(links, active, result.T_world_scan, param);
    const multiview_detail::Steps steps = multiview_detail::solve(system, config);
    result.pivot_ratio = steps.pivot_ratio;
    const auto max_step = multiview_detail::apply_steps(steps, param, result.T_world_scan);
    const std::optional<std::size_t> dropped =
        prune_worst_link(links, result.T_world_scan, config, connected, active);
    if (dropped) {
        result.links[*dropped].dropped = true;
        result.links[*dropped].dropped_in_round = result.rounds;
    }
    return !dropped && step_below_tolerance(max_step, config);
}

}  // namespace

MultiviewRefinementResult refine_multiview(std::span<const Pose> T_world_scan_initial,
                                           std::span<const MultiviewLink> links,
                                           const MultiviewRefinementConfig& config) {
    const auto start = std::chrono::steady_clock::now();
    MultiviewRefinementResult result;
    result.T_world_scan.assign(T_world_scan_initial.begin(), T_world_scan_initial.end());
    result.links.resize(links.size());
    if (!valid_input(T_world_scan_initial, links, config)) return result;

    std::vector<bool> active = initial_links(links, T_world_scan_initial, config, result.links);
    Parametrisation param =
        multiview_detail::make_parametrisation(T_world_scan_initial, links, active);
    while (result.rounds < config.max_rounds && !result.converged) {
        ++result.rounds;
        result.converged = run_round(T_world_scan_initial, links, config, param, active, result);
    }
    // A link dropped in the last round may have cut scans off: they keep their input pose.
    restore_disconnected(T_world_scan_initial,
                         multiview_detail::connected_scans(T_world_scan_initial.size(),
                                                           config.fixed_scan_index, links, active),
                         result);
    for (std::size_t l = 0; l < links.size(); ++l) {
        result.links[l].rms_after_m = multiview_detail::link_rms_m(links[l], result.T_world_scan);
    }
    result.status = final_status(result, config);
    result.time_s = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    return result;
}

}  // namespace anascan
