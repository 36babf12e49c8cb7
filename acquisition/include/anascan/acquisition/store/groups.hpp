#pragma once
/// \file
/// Which group of a session is "the model": one rule for the coverage, the truth
/// comparison, the exports, the live capture and the field app.

#include <span>
#include <vector>

#include "anascan/acquisition/store/session_store.hpp"

namespace anascan::acquisition {

/// The group id that occurs most often in `member_groups` (one entry per member scan), the
/// lowest id on a tie. Negative ids are not groups. -1 when there is none.
int largest_group_id(std::span<const int> member_groups);

/// Whether a scan counts as a member of its group: registered, not excluded, with a pose.
bool counts_in_group(const ScanRecord& scan);

/// The group with the most scans that count_in_group (lowest id on a tie); -1: none.
/// Excluded scans never count.
int largest_group(const std::vector<ScanRecord>& scans);

}  // namespace anascan::acquisition
