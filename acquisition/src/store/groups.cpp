#include "anascan/acquisition/store/groups.hpp"

#include <map>

namespace anascan::acquisition {

int largest_group_id(std::span<const int> member_groups) {
    std::map<int, std::size_t> sizes;
    for (const int group : member_groups)
        if (group >= 0) ++sizes[group];
    int best = -1;
    std::size_t best_size = 0;
    for (const auto& [group, size] : sizes)
        if (size > best_size) best = group, best_size = size;
    return best;
}

bool counts_in_group(const ScanRecord& scan) {
    return scan.state == ScanState::kRegistered && !scan.excluded && scan.pose.has_value();
}

int largest_group(const std::vector<ScanRecord>& scans) {
    std::vector<int> groups;
    for (const ScanRecord& scan : scans)
        if (counts_in_group(scan)) groups.push_back(scan.group);
    return largest_group_id(groups);
}

ModelStrength ModelMembers::strength() const {
    if (joined.size() < 2) return ModelStrength::kNone;
    if (joined.size() == 2 && active >= 3) return ModelStrength::kUnconfirmedPair;
    return 2 * joined.size() < active ? ModelStrength::kPartial : ModelStrength::kWhole;
}

ModelMembers model_members(const std::vector<ScanRecord>& scans) {
    ModelMembers out;
    const int group = largest_group(scans);
    for (const ScanRecord& s : scans) {
        if (s.excluded) continue;
        ++out.active;
        if (s.state == ScanState::kFlagged) ++out.flagged;
        if (counts_in_group(s) && s.group == group) out.joined.push_back(s.seq);
    }
    return out;
}

}  // namespace anascan::acquisition
