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

}  // namespace anascan::acquisition
