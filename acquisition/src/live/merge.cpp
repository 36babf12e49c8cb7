// LiveRegistrar: merging two groups by global registration of their whole stone-only clouds,
// with the stone's up as an acquisition-aware constraint. The sensors stand above a stone on
// the ground, so each group's mean viewing direction is its "up": a group from the same side
// (no turn-over in between) keeps it, a group after a turn-over has it turned down. On a
// near-symmetric block this rejects the look-alike that maps the old top face onto the new
// top (the old bottom): measured on the demo session (docs/live-registration.md).
#include <algorithm>
#include <cmath>
#include <map>

#include "live/state.hpp"

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
    const bool few = std::min(members(target).size(), members(source).size()) <
                     config.merges.min_group_scans_for_up;
    const double slack_deg = few ? config.merges.few_scans_up_slack_deg : 0.0;
    const bool turned = group_side(target) != group_side(source);
    return AxisConstraint{
        .source_axis = *up_source,
        .target_axis = *up_target,
        .min_angle_deg = turned ? 90.0 + slack_deg : 0.0,
        .max_angle_deg = turned ? 180.0 : config.merges.max_same_side_up_deg + slack_deg};
}

std::optional<Pose> LiveRegistrar::State::clear_whole_group_match(
    const GlobalRegistrationResult& g, const Eigen::Vector3d& source_centroid_m) const {
    // Merged group clouds blend several scans, so their fit is looser than one link's: the
    // right merge of the demo session's sides had 0.26-0.39 mm against links of ~0.18 mm.
    const double gate_m =
        config.merges.whole_group_rms_factor * std::min(rms_gate(), limits().max_rms_m);
    // The best fit, not the largest overlap: on the demo session a pose slid by 21 mm had
    // 57 % overlap at 0.50 mm, the right one 55 % at 0.26 mm.
    const HypothesisOutcome* best = nullptr;
    for (const HypothesisOutcome& h : g.hypotheses)
        if (h.verified && (!best || h.fine.rms_m < best->fine.rms_m)) best = &h;
    if (!best || best->fine.rms_m > gate_m) return std::nullopt;
    // A stone turned over about another horizontal axis also turns its up down, and a
    // group can slide along a long face: such look-alikes may verify too. The best pose
    // must fit clearly better than every other verified one.
    for (const HypothesisOutcome& h : g.hypotheses) {
        if (!h.verified || &h == best) continue;
        const bool same =
            live::poses_agree(best->fine.T_target_source, h.fine.T_target_source, source_centroid_m,
                              config.votes.rotation_deg, config.votes.displacement_m);
        if (!same && best->fine.rms_m > config.merges.whole_group_rms_ratio * h.fine.rms_m)
            return std::nullopt;
    }
    return orthonormalized(best->fine.T_target_source);
}

std::vector<PoseUpdate> LiveRegistrar::State::merge_whole_groups() {
    // Without the session's own noise level (enough links) a look-alike cannot be told from
    // the right pose by its RMS: wait.
    if (!config.merges.whole_groups || !std::isfinite(rms_gate())) return {};
    const std::map<int, std::vector<std::size_t>> in = group_members();
    std::vector<int> ids;
    for (const auto& [g, scans_of_g] : in) ids.push_back(g);
    // Members are most recent first: the back is the group's first scan.
    const auto size = [&](int g) { return in.at(g).size(); };
    const auto first_scan = [&](int g) { return in.at(g).back(); };
    for (std::size_t b = 1; b < ids.size(); ++b) {
        for (std::size_t a = 0; a < b; ++a) {
            // Tried again only once one of the groups has grown by half (each try costs
            // seconds; doubling was too rare: a side of 12 scans last tried at 7 never was).
            const std::size_t size_a = size(ids[a]), size_b = size(ids[b]);
            const std::size_t smaller = std::min(size_a, size_b), larger = std::max(size_a, size_b);
            const std::size_t first_a = first_scan(ids[a]), first_b = first_scan(ids[b]);
            auto [it, first] = whole_merge_tried.try_emplace(
                {std::min(first_a, first_b), std::max(first_a, first_b)}, smaller, larger);
            const auto grown = [](std::size_t now, std::size_t then) {
                return 2 * now >= 3 * then;
            };
            if (!first && !grown(smaller, it->second.first) && !grown(larger, it->second.second))
                continue;
            it->second = {smaller, larger};
            // The smaller group is the source: verification asks for overlap of the source.
            const bool a_smaller = size_a < size_b;
            const int source_id = a_smaller ? ids[a] : ids[b];
            const int target_id = a_smaller ? ids[b] : ids[a];
            GlobalRegistrationConfig global = config.global.registration;
            global.axis_constraint = up_constraint(target_id, source_id);
            const PointCloud source = group_cloud(source_id);
            const GlobalRegistrationResult g =
                register_global(source, group_cloud(target_id), global);
            ++report.merge_attempts;
            // One try per call: it costs seconds, and a new scan may be waiting.
            const std::optional<Pose> T = clear_whole_group_match(g, live::cloud_centroid(source));
            if (!T) return {};
            // Into the lower id: T_a_b.
            return merge(ids[a], ids[b], a_smaller ? Pose(T->inverse()) : *T);
        }
    }
    return {};
}

}  // namespace anascan::acquisition
