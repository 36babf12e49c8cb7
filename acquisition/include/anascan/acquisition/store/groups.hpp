#pragma once
/// \file
/// Which group of a session is "the model": one rule for the coverage, the truth
/// comparison, the exports, the live capture and the field app.

#include <cstddef>
#include <cstdint>
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

/// How much of a session its model holds, and how far that can be trusted.
enum class ModelStrength {
    kNone,             ///< No two scans joined: no model.
    kUnconfirmedPair,  ///< Two scans of three or more: one fit that no other scan confirms
                       ///< (two views of a flat face fit anywhere along it).
    kPartial,          ///< Fewer than half of the scans.
    kWhole,            ///< At least half of the scans (or the only two).
};

struct ModelMembers {
    std::vector<std::int64_t> joined;  ///< The largest group's scans that count, by seq.
    std::size_t active = 0;            ///< Scans not excluded.
    std::size_t flagged = 0;           ///< Of those, taken out of their group.
    ModelStrength strength() const;
};

ModelMembers model_members(const std::vector<ScanRecord>& scans);

}  // namespace anascan::acquisition
