// choose_take_out and describe: which scans of a disagreeing group to take out, and the
// words for a pair's disagreement.
#include <algorithm>
#include <cstdio>
#include <string>

#include "anascan/processing/evaluation/group_consistency.hpp"

namespace anascan {
namespace {

/// Disagreeing pairs of each scan among the kept ones.
std::vector<std::size_t> disagreements(const GroupConsistency& group,
                                       const std::vector<bool>& kept) {
    std::vector<std::size_t> count(group.scans.size(), 0);
    for (const PairConsistency& p : group.pairs) {
        if (p.agrees || !kept[p.a] || !kept[p.b]) continue;
        ++count[p.a];
        ++count[p.b];
    }
    return count;
}

std::string name_of(std::size_t i, std::span<const std::string> names) {
    return i < names.size() ? names[i] : "scan " + std::to_string(i);
}

std::string percent(double fraction) {
    char text[32];
    std::snprintf(text, sizeof(text), "%.0f %%", fraction * 100.0);
    return text;
}

/// How strongly a pair disagrees: its largest violation figure.
double severity(const PairConsistency& p) {
    return std::max({p.b_seen_from_a.violation_fraction, p.a_seen_from_b.violation_fraction,
                     p.crossing_fraction});
}

}  // namespace

void choose_take_out(GroupConsistency& group) {
    std::vector<bool> kept(group.scans.size(), true);
    group.take_out.clear();
    group.consistent = std::all_of(group.pairs.begin(), group.pairs.end(),
                                   [](const PairConsistency& p) { return p.agrees; });
    for (ScanConsistency& s : group.scans) s = {};
    for (const PairConsistency& p : group.pairs) {
        for (const std::size_t i : {p.a, p.b}) {
            ++group.scans[i].overlapping;
            if (p.agrees) continue;
            ++group.scans[i].disagreeing;
            std::optional<std::size_t>& worst = group.scans[i].worst_pair;
            if (!worst || severity(group.pairs[*worst]) < severity(p))
                worst = &p - group.pairs.data();
        }
    }
    for (;;) {
        const std::vector<std::size_t> count = disagreements(group, kept);
        std::size_t worst = 0;
        for (std::size_t i = 1; i < count.size(); ++i)
            if (count[i] >= count[worst]) worst = i;  // Ties: the later placement.
        if (count.empty() || count[worst] == 0) break;
        kept[worst] = false;
        group.scans[worst].taken_out = true;
        group.take_out.push_back(worst);
    }
}

std::string describe(const PairConsistency& p, std::span<const std::string> names) {
    std::string text = name_of(p.b, names) + " disagrees with " + name_of(p.a, names) + ": ";
    if (p.agrees) return name_of(p.b, names) + " agrees with " + name_of(p.a, names);
    if (p.reason == "free space") {
        const bool b_in_a =
            p.b_seen_from_a.violation_fraction >= p.a_seen_from_b.violation_fraction;
        const FreeSpaceResult& r = b_in_a ? p.b_seen_from_a : p.a_seen_from_b;
        return text + std::to_string(r.violations) + " of " + std::to_string(r.in_view) +
               " points of " + name_of(b_in_a ? p.b : p.a, names) + " (" +
               percent(r.violation_fraction) + ") lie in the space " +
               name_of(b_in_a ? p.a : p.b, names) + "'s sensor saw empty";
    }
    char figures[200];
    if (p.reason == "surfaces apart") {
        std::snprintf(figures, sizeof(figures),
                      "its surface lies %.2f mm (median of %zu near points) from the other's, "
                      "%.1f times their noise",
                      p.median_offset_m * 1e3, p.near_samples, p.median_offset_m / p.noise_m);
        return text + figures;
    }
    std::snprintf(figures, sizeof(figures),
                  "normals cross on %s of %zu near points (median angle %.1f°, crossing above "
                  "%.1f°)",
                  percent(p.crossing_fraction).c_str(), p.near_samples, p.median_normal_angle_deg,
                  p.crossing_angle_deg);
    return text + figures;
}

}  // namespace anascan
