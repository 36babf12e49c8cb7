// LiveRegistrar: the group consistency check after each refinement. A scan placed by links
// that each fit can still contradict the other scans of its group it now overlaps (a plane
// fits a plane anywhere); the scans whose removal restores agreement are taken out of the
// model and flagged with their worst disagreement.
#include <algorithm>
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

}  // namespace

void LiveRegistrar::State::check_groups() {
    if (!config.consistency.enabled) return;
    for (const int g : groups()) {
        if (interrupted()) return;
        check_group(g);
    }
}

void LiveRegistrar::State::check_group(int g) {
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
    for (std::size_t k : result.take_out) {
        live::ScanEntry& e = scans[ids[k]];
        const std::optional<std::size_t> worst = result.scans[k].worst_pair;
        e.flagged = "contradicts its group (disagrees with " +
                    std::to_string(result.scans[k].disagreeing) + " of " +
                    std::to_string(result.scans[k].overlapping) + " overlapping scans): " +
                    (worst ? describe(result.pairs[*worst], names) : std::string("?"));
        report.taken_out.push_back({.seq = e.seq, .group = g, .reason = e.flagged});
        e.group = -1;
    }
    if (!result.take_out.empty()) {
        std::erase_if(links, [&](const live::Link& l) {
            return !live::active(scans[l.target]) || !live::active(scans[l.source]);
        });
        ids = members(g);
        std::reverse(ids.begin(), ids.end());
    }
    checked_groups[g] = snapshot(ids, scans);
}

std::optional<std::string> LiveRegistrar::flagged(std::int64_t seq) const {
    const auto it = state_->index_of_seq.find(seq);
    if (it == state_->index_of_seq.end() || state_->scans[it->second].flagged.empty())
        return std::nullopt;
    return state_->scans[it->second].flagged;
}

}  // namespace anascan::acquisition
