// LiveRegistrar: merging two groups by global registration of their whole stone-only clouds,
// with the stone's up as an acquisition-aware constraint. The sensors stand above a stone on
// the ground, so each group's mean viewing direction is its "up": a group from the same side
// (no turn-over in between) keeps it, a group after a turn-over has it turned down. On a
// near-symmetric block this rejects the look-alike that maps the old top face onto the new
// top (the old bottom): measured on the demo session (docs/live-registration.md).
#include <algorithm>

#include "live_registration_state.hpp"

namespace anascan::acquisition {

std::optional<Eigen::Vector3d> LiveRegistrar::State::group_up(int group) const {
    const std::vector<std::size_t> ids = members(group);
    if (ids.empty()) return std::nullopt;
    Eigen::Vector3d sum = Eigen::Vector3d::Zero();
    for (std::size_t i : ids) {
        const live::ScanEntry& e = scans[i];
        const Eigen::Vector3d view =
            e.T_group_scan * e.sensor_origin_m - e.T_group_scan * e.centroid_m;
        if (view.norm() > 0.0) sum += view.normalized();
    }
    // Views from all around cancel sideways; a few views from one direction do not.
    if (sum.norm() < 0.3 * static_cast<double>(ids.size())) return std::nullopt;
    return sum.normalized();
}

int LiveRegistrar::State::group_side(int group) const {
    const std::vector<std::size_t> ids = members(group);  // Most recent first.
    return ids.empty() ? 0 : scans[ids.front()].side;
}

std::optional<AxisConstraint> LiveRegistrar::State::up_constraint(int target, int source) const {
    const std::optional<Eigen::Vector3d> up_target = group_up(target);
    const std::optional<Eigen::Vector3d> up_source = group_up(source);
    if (!up_target || !up_source) return std::nullopt;
    // A group of a few scans has a viewing direction, not yet an up: the sensor looks down
    // on the stone from above, but from one side (up to 70° off the vertical).
    const bool few =
        std::min(members(target).size(), members(source).size()) < config.min_group_scans_for_up;
    const double slack_deg = few ? config.few_scans_up_slack_deg : 0.0;
    const bool turned = group_side(target) != group_side(source);
    return AxisConstraint{
        .source_axis = *up_source,
        .target_axis = *up_target,
        .min_angle_deg = turned ? 90.0 + slack_deg : 0.0,
        .max_angle_deg = turned ? 180.0 : config.max_same_side_up_deg + slack_deg};
}

std::vector<PoseUpdate> LiveRegistrar::State::merge_whole_groups() {
    if (!config.whole_group_merges) return {};
    const std::vector<int> ids = groups();
    for (std::size_t b = 1; b < ids.size(); ++b) {
        for (std::size_t a = 0; a < b; ++a) {
            // Tried again only once the two groups have doubled (each try costs seconds).
            const std::size_t scans_now = members(ids[a]).size() + members(ids[b]).size();
            std::size_t& tried = whole_merge_tried[{ids[a], ids[b]}];
            if (scans_now < 2 * tried) continue;
            tried = scans_now;
            // The smaller group is the source: verification asks for overlap of the source.
            const bool a_smaller = members(ids[a]).size() < members(ids[b]).size();
            const int source_id = a_smaller ? ids[a] : ids[b];
            const int target_id = a_smaller ? ids[b] : ids[a];
            GlobalRegistrationConfig global = config.global;
            global.axis_constraint = up_constraint(target_id, source_id);
            const GlobalRegistrationResult g =
                register_global(group_cloud(source_id), group_cloud(target_id), global);
            ++report.merge_attempts;
            // One try per call: it costs seconds, and a new scan may be waiting.
            if (g.status != GlobalRegistrationStatus::kSuccess || g.rms_m > rms_gate()) return {};
            // Into the lower id: T_a_b.
            return merge(ids[a], ids[b],
                         a_smaller ? Pose(g.T_target_source.inverse()) : g.T_target_source);
        }
    }
    return {};
}

}  // namespace anascan::acquisition
