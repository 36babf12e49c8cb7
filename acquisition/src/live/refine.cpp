// LiveRegistrar::refine: group merges by global registration of stone-only scans,
// multi-view links (links.cpp), features ahead of need, multi-view refinement.
#include <algorithm>
#include <cmath>
#include <map>

#include "anascan/processing/spatial/kdtree.hpp"
#include "anascan/processing/spatial/voxel_grid.hpp"
#include "live/state.hpp"
#include "live/votes.hpp"

namespace anascan::acquisition {
namespace {

using live::ScanEntry;
using Clock = std::chrono::steady_clock;

}  // namespace

Eigen::Vector3d live::cloud_centroid(const PointCloud& cloud) {
    Eigen::Vector3d sum = Eigen::Vector3d::Zero();
    for (std::size_t i = 0; i < cloud.size(); ++i) sum += cloud.world_position(i);
    return cloud.empty() ? sum : Eigen::Vector3d(sum / static_cast<double>(cloud.size()));
}

std::vector<PoseUpdate> LiveRegistrar::State::refine_groups() {
    std::vector<PoseUpdate> updates;
    for (const int g : groups()) refine_group(g, updates);
    return updates;
}

void LiveRegistrar::State::refine_group(int g, std::vector<PoseUpdate>& updates) {
    std::vector<std::size_t> group_scans = members(g);
    std::reverse(group_scans.begin(), group_scans.end());  // Ascending: first scan fixed.
    std::map<std::size_t, std::size_t> local;
    std::vector<Pose> poses;
    for (std::size_t i : group_scans) {
        local[i] = poses.size();
        poses.push_back(scans[i].T_group_scan);
    }
    std::vector<MultiviewLink> group_links;
    for (const live::Link& l : links) {
        if (!local.contains(l.target) || !local.contains(l.source)) continue;
        group_links.push_back({.target_index = local[l.target],
                               .source_index = local[l.source],
                               .correspondences = l.correspondences});
    }
    if (poses.size() < 2 || group_links.empty()) return;
    MultiviewRefinementConfig mv = config.links.multiview;
    mv.fixed_scan_index = 0;
    const MultiviewRefinementResult refined = refine_multiview(poses, group_links, mv);
    const bool usable = refined.status == MultiviewStatus::kConverged ||
                        refined.status == MultiviewStatus::kMaxRounds ||
                        refined.status == MultiviewStatus::kDisconnected;
    if (!usable) return;
    ++report.groups_refined;
    for (std::size_t m = 0; m < group_scans.size(); ++m) {
        ScanEntry& e = scans[group_scans[m]];
        const PoseDifference d = pose_difference(e.T_group_scan, refined.T_world_scan[m]);
        if (d.rotation_deg < 1e-6 && d.translation_m < 1e-9) continue;
        e.T_group_scan = refined.T_world_scan[m];
        updates.push_back({.seq = e.seq, .group = g, .T_group_scan = e.T_group_scan});
    }
}

PointCloud LiveRegistrar::State::group_cloud(int group) const {
    PointCloud merged;
    for (std::size_t i : members(group))
        append(merged, transformed(scans[i].cloud, scans[i].T_group_scan));
    return voxel_downsample(merged, {.voxel_size_m = config.prepare.voxel_size_m});
}

Pose LiveRegistrar::State::refined_merge(int into, int from, const Pose& T_into_from) const {
    // The voted transform agrees within the votes' tolerance (a centimetre): fine register
    // the whole groups (stone only) so that the merged scans' links form at once.
    const PointCloud target = group_cloud(into);
    const PointCloud source = group_cloud(from);
    if (target.empty() || source.empty()) return T_into_from;
    const KdTree tree(target.positions);
    const FineRegistrationResult fine =
        register_fine(source, target, tree, T_into_from, config.hypotheses.fine);
    const bool agrees =
        live::poses_agree(T_into_from, fine.T_target_source, live::cloud_centroid(source),
                          config.votes.rotation_deg, config.votes.displacement_m);
    const live::VerificationLimits absolute{
        .max_rms_m = config.verify.max_rms_voxel_factor * config.prepare.voxel_size_m,
        .max_normal_deviation_deg = config.verify.max_normal_deviation_deg};
    LiveRegistrationConfig relaxed = config;
    relaxed.verify.min_overlap_fraction = config.links.min_overlap_fraction;  // Other faces too.
    if (!agrees || !live::rejection(fine, relaxed, absolute).empty()) return T_into_from;
    return orthonormalized(fine.T_target_source);
}

std::vector<PoseUpdate> LiveRegistrar::State::merge(int into, int from,
                                                    const Pose& T_into_from_voted) {
    const Pose T_into_from = refined_merge(into, from, T_into_from_voted);
    std::vector<PoseUpdate> updates;
    // Until `into` next passes its check the moved scans are one part (consistency.cpp); the
    // parts merged into `from` before are inside it.
    live::MergedPart part{.from = from};
    for (std::size_t i = 0; i < scans.size(); ++i) {
        ScanEntry& e = scans[i];
        if (e.group != from) continue;
        part.scans.push_back(i);
        e.group = into;
        e.T_group_scan = orthonormalized(T_into_from * e.T_group_scan);
        if (live::active(e))
            updates.push_back({.seq = e.seq, .group = into, .T_group_scan = e.T_group_scan});
    }
    unchecked_merges.erase(from);
    unchecked_merges[into].push_back(std::move(part));
    ++report.merges;
    return updates;
}

void LiveRegistrar::State::vote_scan_pair(std::size_t i, std::size_t j, live::PoseVotes& box) {
    const GlobalRegistrationResult g = register_global(scans[j].cloud, features(j), scans[i].cloud,
                                                       features(i), config.global.registration);
    for (const HypothesisOutcome& h : g.hypotheses) {
        if (!h.verified || h.fine.rms_m > rms_gate()) continue;
        const Pose T_a_b =
            scans[i].T_group_scan * h.fine.T_target_source * scans[j].T_group_scan.inverse();
        box.add(T_a_b, i * scans.size() + j, scans[j].T_group_scan * scans[j].centroid_m);
    }
}

std::optional<std::vector<PoseUpdate>> LiveRegistrar::State::merge_by_votes(
    int a, int b, const std::vector<std::size_t>& in_a, const std::vector<std::size_t>& in_b,
    std::size_t& attempts) {
    live::PoseVotes& box =
        merge_votes.try_emplace({a, b}, config.votes.rotation_deg, config.votes.displacement_m)
            .first->second;
    for (std::size_t j : in_b) {
        for (std::size_t i : in_a) {
            if (attempts >= config.merges.max_attempts) return std::vector<PoseUpdate>{};
            // Each try is a global registration (0.1-0.3 s): a waiting scan comes first,
            // the pairs not tried yet (not marked) are the next call's.
            if (interrupted()) return std::vector<PoseUpdate>{};
            if (!merge_tried.insert({i, j}).second) continue;
            ++attempts;
            vote_scan_pair(i, j, box);
            if (const auto T = box.winner(config.votes.min_count, config.votes.ratio))
                return merge(a, b, *T);
        }
    }
    return std::nullopt;
}

std::vector<PoseUpdate> LiveRegistrar::State::merge_groups() {
    const std::map<int, std::vector<std::size_t>> in = group_members();
    std::vector<int> ids;
    for (const auto& [g, scans_of_g] : in) ids.push_back(g);
    // Members are most recent first: the front is the group's side.
    const auto side = [&](int g) { return scans[in.at(g).front()].side; };
    std::size_t attempts = 0;
    for (std::size_t b = 1; b < ids.size(); ++b) {
        for (std::size_t a = 0; a < b; ++a) {
            // Across a turn-over single scans match by look-alike poses that fit only a few
            // times worse than the right one: without the session's RMS gate (enough
            // links), their votes can carry a wrong merge (seen on the demo session when
            // the capture kept the background too busy for links). Wait for the gate.
            if (side(ids[a]) != side(ids[b]) && !std::isfinite(rms_gate())) continue;
            if (auto done = merge_by_votes(ids[a], ids[b], in.at(ids[a]), in.at(ids[b]), attempts))
                return std::move(*done);
        }
    }
    return {};
}

std::vector<PoseUpdate> LiveRegistrar::refine(const std::function<bool()>& interrupt) {
    const Clock::time_point start = Clock::now();
    State& s = *state_;
    s.report = {};
    s.interrupt = interrupt;
    std::map<std::int64_t, PoseUpdate> changed;
    for (const PoseUpdate& u : s.merge_by_sequence()) changed[u.seq] = u;
    if (s.report.merges == 0 && !s.interrupted())
        for (const PoseUpdate& u : s.merge_whole_groups()) changed[u.seq] = u;
    if (s.report.merges == 0 && !s.interrupted())
        for (const PoseUpdate& u : s.merge_groups()) changed[u.seq] = u;
    // Links before features: links are every scan's share of the final solve (left
    // undone, they pile up for the end of the capture), features are computed on demand.
    if (!s.interrupted()) s.report.new_links = s.make_links();
    std::size_t described = 0;
    for (std::size_t i = 0;
         i < s.scans.size() && described < s.config.max_features_per_refine && !s.interrupted();
         ++i) {
        if (!live::active(s.scans[i]) || s.scans[i].features) continue;
        s.features(i);
        ++described;
    }
    // An interrupted round leaves the solve to the next call: the new scan comes first.
    if (!s.interrupted())
        for (const PoseUpdate& u : s.refine_groups()) changed[u.seq] = u;
    // The solved poses checked against each other: contradicting scans leave their group.
    std::vector<PoseUpdate> regrouped;
    if (!s.interrupted()) regrouped = s.check_groups();
    for (const LiveTakenOut& t : s.report.taken_out) changed.erase(t.seq);
    for (const PoseUpdate& u : regrouped) changed[u.seq] = u;
    s.interrupt = {};
    s.report.time_s = seconds_since(start);
    std::vector<PoseUpdate> out;
    for (const auto& [seq, u] : changed) out.push_back(u);
    return out;
}

}  // namespace anascan::acquisition
