#pragma once
/// \file
/// Each scan of a stored session checked against the rest of its group at once
/// (processing's `union_pulls`): a scan placed by one link can slide along a face that fits
/// anywhere along it, with every pair agreeing; registered against all the others it moves
/// back. Found after a capture (`anascan capture` flags it) and by `anascan session
/// consistency`. See docs/scan-registration.md "Union pull".

#include <cstdint>
#include <functional>
#include <string>
#include <vector>

#include "anascan/acquisition/store/session_store.hpp"
#include "anascan/processing/evaluation/union_pull.hpp"

namespace anascan::acquisition {

/// One scan of a group and how the rest of the group moves it.
struct GroupPull {
    std::int64_t seq = 0;
    int group = -1;
    std::size_t group_scans = 0;
    ScanPull pull;
    /// For a pulled scan: what happened and what to do, in the operator's words.
    std::string message() const;
};

/// Every scan of every group of at least 3 scans that count (registered, with a pose, not
/// excluded), reduced as the live registrar reduces them (stone only, 2 mm voxel, fresh
/// normals). `progress` (optional) is called before each group with its id and size.
Expected<std::vector<GroupPull>> group_pulls(
    const SessionStore& store, const UnionPullConfig& config = {},
    const std::function<void(int group, std::size_t scans)>& progress = {});

/// Marks each pulled scan flagged (its reason in the quality JSON) with a
/// "registration-flagged" event, as the live registrar's group check does; returns how many.
Expected<std::size_t> flag_pulled(SessionStore& store, const std::vector<GroupPull>& pulls);

}  // namespace anascan::acquisition
