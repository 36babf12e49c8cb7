// LiveRegistrar: what stays of a group after scans were taken out. A scan held to the group
// only through scans now taken out has no evidence left for its pose in the group: pairs of
// the remaining scans that overlap and agree are what ties them together, and each part that
// no such pair joins to the rest becomes a group of its own (merged back later only by a
// merge that verifies, and is checked again).
#include <algorithm>
#include <map>
#include <numeric>

#include "live/state.hpp"

namespace anascan::acquisition {
namespace {

std::size_t root(std::vector<std::size_t>& parent, std::size_t i) {
    while (parent[i] != i) i = parent[i] = parent[parent[i]];
    return i;
}

/// Component id (a root position) of every kept position; kept positions of one unit only
/// are joined.
std::vector<std::size_t> components(const GroupConsistency& result, const live::Verdicts& v) {
    std::vector<std::size_t> parent(v.reasons.size());
    std::iota(parent.begin(), parent.end(), std::size_t{0});
    for (const PairConsistency& p : result.pairs) {
        if (!p.agrees || !v.reasons[p.a].empty() || !v.reasons[p.b].empty() ||
            v.unit[p.a] != v.unit[p.b])
            continue;
        const std::size_t a = root(parent, p.a), b = root(parent, p.b);
        parent[std::max(a, b)] = std::min(a, b);  // The earliest position is the root.
    }
    for (std::size_t k = 0; k < parent.size(); ++k) parent[k] = root(parent, k);
    return parent;
}

}  // namespace

void LiveRegistrar::State::split_unsupported(int g, const std::vector<std::size_t>& ids,
                                             const GroupConsistency& result,
                                             const live::Verdicts& v,
                                             std::vector<PoseUpdate>& regrouped) {
    const std::vector<std::string>& reasons = v.reasons;
    const std::vector<std::size_t> component = components(result, v);
    std::size_t first_kept = ids.size();  // The earliest of the group's own scans kept.
    for (std::size_t k = 0; k < ids.size() && first_kept == ids.size(); ++k)
        if (reasons[k].empty() && v.unit[k] == 0) first_kept = k;
    if (first_kept == ids.size()) return;
    std::map<std::size_t, int> new_group;  // By component root (its earliest position).
    std::map<std::size_t, Pose> T_first;   // The root's pose: the new group's frame.
    for (std::size_t k = 0; k < ids.size(); ++k)
        if (reasons[k].empty()) T_first.try_emplace(component[k], scans[ids[k]].T_group_scan);
    for (std::size_t k = 0; k < ids.size(); ++k) {
        if (!reasons[k].empty() || component[k] == component[first_kept]) continue;
        const auto [it, opened] = new_group.try_emplace(component[k], next_group);
        if (opened) ++next_group;
        live::ScanEntry& e = scans[ids[k]];
        e.group = it->second;
        e.T_group_scan = orthonormalized(T_first.at(component[k]).inverse() * e.T_group_scan);
        regrouped.push_back({.seq = e.seq, .group = e.group, .T_group_scan = e.T_group_scan});
        const std::string why = v.unit[k] != 0 ? v.moved[k]
                                               : "nothing ties it to scan " +
                                                     std::to_string(scans[ids[first_kept]].seq) +
                                                     " of group " + std::to_string(g) +
                                                     " once the contradicting scans were taken out";
        report.split_off.push_back({.seq = e.seq,
                                    .group = g,
                                    .reason = why + "; now in group " + std::to_string(e.group)});
    }
}

}  // namespace anascan::acquisition
