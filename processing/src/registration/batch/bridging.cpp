// Bridging rounds of register_scans with pair pruning: when the verified pairs leave
// several groups, the scans at the border of each group try their most similar scans of
// other groups (by the pruning votes) that were not matched yet.
//
// Why: pruning keeps a scan's few most similar scans, and on a long object a true
// neighbour can score no higher than look-alikes elsewhere. Measured on 300 wall windows (3
// candidates per scan): one break, none of its three crossing pairs a candidate; window
// 290 had 289 fourth in its list (similarity 0.22, behind its own group's 291 and 292 and
// one look-alike), the noise floor being 0.2-0.3 while ±1 neighbours mostly score 0.36-0.56.
// Ranked among the scans of *other* groups, 289 was 290's first. A group's border scans are
// those with the fewest group members close by under the spanning-tree poses (centres
// nearer than half the sum of the bounding radii): 2 at the end of a chain of windows, 4
// inside it.
//
// Partners are chosen among the *border scans of the other groups* only: two groups can
// only be joined where both have a border (a scan inside a group has its neighbours in the
// group already). At 1000 windows (25 groups after the pairwise stage), ranking a border
// scan's partners among all scans of other groups (~700) left 7 breaks after 4 rounds: the
// true neighbour was not among its 8 most similar, more look-alikes than at 300. Among the
// other groups' border scans only, the rounds joined every break (1000 of 1000 placed, one
// group, 209 bridging pairs, none verified wrongly; docs/scan-registration.md, "Scale").
#include <algorithm>

#include "registration/batch/steps.hpp"

namespace anascan::detail {
namespace {

// Scans of group g with the fewest members of g nearby (ties by index), at most `count`.
std::vector<std::size_t> border_scans(const std::vector<std::size_t>& members,
                                      const std::vector<Eigen::Vector3d>& centre_m,
                                      const std::vector<ScanSummary>& summary, std::size_t count) {
    std::vector<std::pair<std::size_t, std::size_t>> degree;  // (close members, scan)
    for (std::size_t a : members) {
        std::size_t close = 0;
        for (std::size_t b : members) {
            const double reach = 0.5 * (summary[a].radius_m + summary[b].radius_m);
            close += b != a && (centre_m[a] - centre_m[b]).norm() < reach;
        }
        degree.emplace_back(close, a);
    }
    return smallest(std::move(degree), count);
}

}  // namespace

std::vector<std::pair<std::size_t, std::size_t>> bridge_pairs(
    const PairVotes& votes, const PoseGraph& graph, const std::vector<ScanSummary>& summary,
    const std::set<std::pair<std::size_t, std::size_t>>& matched,
    const ScanRegistrationConfig& config) {
    const std::size_t n = votes.n;
    std::vector<std::vector<std::size_t>> members(graph.group_count);
    std::vector<Eigen::Vector3d> centre_m(n, Eigen::Vector3d::Zero());
    for (std::size_t i = 0; i < n; ++i) {
        if (graph.group[i] < 0) continue;
        members[static_cast<std::size_t>(graph.group[i])].push_back(i);
        centre_m[i] = graph.T_root_scan[i] * summary[i].centre_m;
    }
    std::vector<bool> border(n, false);
    for (const std::vector<std::size_t>& group : members) {
        for (std::size_t i : border_scans(group, centre_m, summary, config.bridge_scans_per_group))
            border[i] = true;
    }
    std::set<std::pair<std::size_t, std::size_t>> chosen;
    for (std::size_t i = 0; i < n; ++i) {
        if (!border[i]) continue;
        const auto other_border = [&](std::size_t j) {
            return border[j] && graph.group[j] != graph.group[i] &&
                   !matched.contains({std::max(i, j), std::min(i, j)});
        };
        for (std::size_t j : votes.most_similar(i, config.bridge_partners_per_scan, other_border))
            chosen.emplace(std::max(i, j), std::min(i, j));
    }
    return {chosen.begin(), chosen.end()};
}

}  // namespace anascan::detail
