// LiveRegistrar: the group consistency check after each refinement. A scan placed by links
// that each fit can still contradict the other scans of its group it now overlaps (a plane
// fits a plane anywhere). A check that fails after a merge is evidence against the merge: the
// group merged in leaves whole (with the merges made onto it), then the scans whose removal
// restores agreement leave one at a time, each flagged with its worst disagreement. What
// stays is split where nothing ties it together any more (consistency_split.cpp).
#include <algorithm>
#include <set>
#include <string>
#include <vector>

#include "anascan/processing/evaluation/group_consistency.hpp"
#include "live/state.hpp"
#include "live/votes.hpp"

namespace anascan::acquisition {
namespace {

bool unchanged(const live::CheckedGroup& checked, const std::vector<std::size_t>& ids,
               const std::vector<live::ScanEntry>& scans, const LiveConsistencyConfig& config) {
    if (checked.scans != ids) return false;
    for (std::size_t k = 0; k < ids.size(); ++k) {
        const live::ScanEntry& e = scans[ids[k]];
        if (!live::poses_agree(checked.poses[k], e.T_group_scan, e.centroid_m, config.recheck_deg,
                               config.recheck_m))
            return false;
    }
    return true;
}

live::CheckedGroup snapshot(const std::vector<std::size_t>& ids,
                            const std::vector<live::ScanEntry>& scans) {
    live::CheckedGroup c{.scans = ids};
    for (std::size_t i : ids) c.poses.push_back(scans[i].T_group_scan);
    return c;
}

/// The scans still in the group (no reason, not moved) that disagree, taken out one at a time
/// until the rest agree (`choose_take_out` on the pairs between them).
void take_out_one_by_one(const GroupConsistency& result, const std::vector<std::string>& names,
                         live::Verdicts& v) {
    std::vector<std::string>& reasons = v.reasons;
    GroupConsistency kept = result;
    std::erase_if(kept.pairs, [&](const PairConsistency& p) {
        return !reasons[p.a].empty() || !reasons[p.b].empty() || v.unit[p.a] != 0 ||
               v.unit[p.b] != 0;
    });
    choose_take_out(kept);
    for (const std::size_t k : kept.take_out) {
        const std::optional<std::size_t> worst = kept.scans[k].worst_pair;
        v.disagreements[k] = worst ? kept.pairs[*worst].reason : std::string();
        reasons[k] = "contradicts its group (disagrees with " +
                     std::to_string(kept.scans[k].disagreeing) + " of " +
                     std::to_string(kept.scans[k].overlapping) + " overlapping scans): " +
                     (worst ? describe(kept.pairs[*worst], names) : std::string("?"));
    }
}

}  // namespace

std::vector<PoseUpdate> LiveRegistrar::State::check_groups() {
    std::vector<PoseUpdate> regrouped;
    if (!config.consistency.enabled) return regrouped;
    for (const int g : groups()) {
        if (interrupted()) break;
        check_group(g, regrouped);
    }
    return regrouped;
}

void LiveRegistrar::State::take_out_merged_parts(int g, const std::vector<std::size_t>& ids,
                                                 const GroupConsistency& result,
                                                 const std::vector<std::string>& names,
                                                 live::Verdicts& v) {
    std::vector<live::MergedPart>& parts = unchecked_merges[g];
    std::string after;  // Set once a part is out: the later parts were merged onto it.
    std::size_t first_out = parts.size();
    for (std::size_t m = 0; m < parts.size(); ++m) {
        const std::set<std::size_t> in(parts[m].scans.begin(), parts[m].scans.end());
        const auto here = [&](std::size_t k) {  // Still in the group, or in this part.
            return v.reasons[k].empty() && v.unit[k] == 0;
        };
        const PairConsistency *inside = nullptr, *across = nullptr;
        for (const PairConsistency& p : result.pairs) {
            if (p.agrees || !here(p.a) || !here(p.b)) continue;
            const bool a_in = in.contains(ids[p.a]), b_in = in.contains(ids[p.b]);
            if (a_in && b_in && !inside) inside = &p;
            if (a_in != b_in && !across) across = &p;
        }
        if (!inside && !across && after.empty()) continue;
        const std::string part = "came in with group " + std::to_string(parts[m].from) + " (" +
                                 std::to_string(in.size()) + " scans) merged into group " +
                                 std::to_string(g);
        // Scans of the part that contradict each other: it leaves whole, flagged. A part
        // that only contradicts the rest (or was merged onto a part now out) leaves as a
        // group of its own: the merge was wrong, not its scans.
        std::string reason;
        if (inside)
            reason = part + ", and that group contradicts itself: " + describe(*inside, names);
        else if (across)
            reason = part + ", and the merge contradicts the group: " + describe(*across, names);
        else
            reason = part + " onto a model that held " + after;
        for (std::size_t k = 0; k < ids.size(); ++k) {
            if (!in.contains(ids[k]) || !here(k)) continue;
            if (inside)
                v.reasons[k] = reason, v.disagreements[k] = inside->reason;
            else
                v.unit[k] = static_cast<int>(m) + 1, v.moved[k] = reason;
        }
        if (after.empty()) after = "group " + std::to_string(parts[m].from) + " (out again)";
        first_out = std::min(first_out, m);
    }
    parts.resize(first_out);
}

void LiveRegistrar::State::check_group(int g, std::vector<PoseUpdate>& regrouped) {
    std::vector<std::size_t> ids = members(g);
    std::reverse(ids.begin(), ids.end());  // Capture order: ties take out the later scan.
    if (ids.size() < 2) return;
    const auto last = checked_groups.find(g);
    if (last != checked_groups.end() && unchanged(last->second, ids, scans, config.consistency))
        return;
    std::vector<ConsistencyScan> group;
    std::vector<std::string> names;
    for (std::size_t i : ids) {
        group.push_back({.cloud = &scans[i].cloud,
                         .T_group_scan = scans[i].T_group_scan,
                         .sensor_origin_scan_m = scans[i].sensor_origin_m});
        names.push_back("scan " + std::to_string(scans[i].seq));
    }
    const GroupConsistency result = check_group_consistency(group, config.consistency.check);
    ++report.groups_checked;
    if (result.consistent) {
        unchecked_merges.erase(g);
        checked_groups[g] = snapshot(ids, scans);
        return;
    }
    // The evidence is against the newest decisions first: a merge that a disagreement touches
    // leaves whole; what still disagrees then leaves one scan at a time.
    live::Verdicts verdicts{.reasons = std::vector<std::string>(ids.size()),
                            .disagreements = std::vector<std::string>(ids.size()),
                            .unit = std::vector<int>(ids.size(), 0),
                            .moved = std::vector<std::string>(ids.size())};
    take_out_merged_parts(g, ids, result, names, verdicts);
    take_out_one_by_one(result, names, verdicts);
    for (std::size_t k = 0; k < ids.size(); ++k) {
        if (verdicts.reasons[k].empty()) continue;
        live::ScanEntry& e = scans[ids[k]];
        e.flagged = verdicts.reasons[k];
        report.taken_out.push_back({.seq = e.seq,
                                    .group = g,
                                    .reason = e.flagged,
                                    .disagreement = verdicts.disagreements[k]});
        e.group = -1;
    }
    split_unsupported(g, ids, result, verdicts, regrouped);
    std::erase_if(links, [&](const live::Link& l) {
        const live::ScanEntry &t = scans[l.target], &s = scans[l.source];
        return !live::active(t) || !live::active(s) || t.group != s.group;
    });
    ids = members(g);
    std::reverse(ids.begin(), ids.end());
    checked_groups[g] = snapshot(ids, scans);
}

std::optional<std::string> LiveRegistrar::flagged(std::int64_t seq) const {
    const auto it = state_->index_of_seq.find(seq);
    if (it == state_->index_of_seq.end() || state_->scans[it->second].flagged.empty())
        return std::nullopt;
    return state_->scans[it->second].flagged;
}

}  // namespace anascan::acquisition
