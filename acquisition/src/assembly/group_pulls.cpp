// group_pulls: each scan of a stored session's groups against the rest of its group.
#include "anascan/acquisition/assembly/group_pulls.hpp"

#include <cstdio>
#include <map>
#include <nlohmann/json.hpp>

#include "anascan/acquisition/live/live_registration.hpp"
#include "anascan/acquisition/store/groups.hpp"

namespace anascan::acquisition {

std::string GroupPull::message() const {
    char text[400];
    std::snprintf(text, sizeof(text),
                  "scan %lld FLAGGED and taken out of group %d: registered against the other %zu "
                  "scans of its group at once it moves %.1f mm and %.3f deg to a better fit "
                  "(rms %.3f -> %.3f mm): it slid along a face that fits anywhere along it; "
                  "register it again, or scan that part again",
                  static_cast<long long>(seq), group, group_scans - 1, pull.moved_m * 1e3,
                  pull.rotation_deg, pull.rms_before_m * 1e3, pull.rms_m * 1e3);
    return text;
}

Expected<std::vector<GroupPull>> group_pulls(
    const SessionStore& store, const UnionPullConfig& config,
    const std::function<void(int, std::size_t)>& progress) {
    auto records = store.scans();
    if (!records) return fail(records.error());
    std::map<int, std::vector<const ScanRecord*>> groups;
    for (const ScanRecord& r : *records)
        if (counts_in_group(r)) groups[r.group].push_back(&r);
    std::vector<GroupPull> out;
    const LiveRegistrationConfig reduction{};
    for (const auto& [group, members] : groups) {
        if (members.size() < 3) continue;
        if (progress) progress(group, members.size());
        std::vector<PointCloud> clouds;
        clouds.reserve(members.size());
        for (const ScanRecord* r : members) {
            auto scan = store.load_scan(r->seq);
            if (!scan) return fail(scan.error());
            auto reduced = reduce_to_stone({.seq = r->seq,
                                            .cloud = std::move(scan->cloud),
                                            .sensor_origin_scan_m = r->sensor_origin_scan_m},
                                           reduction);
            clouds.push_back(reduced ? std::move(*reduced) : PointCloud{});
        }
        std::vector<ConsistencyScan> scans;
        for (std::size_t k = 0; k < members.size(); ++k)
            scans.push_back({.cloud = &clouds[k], .T_group_scan = *members[k]->pose});
        const std::vector<ScanPull> pulls = union_pulls(scans, config);
        for (std::size_t k = 0; k < members.size(); ++k)
            out.push_back({.seq = members[k]->seq,
                           .group = group,
                           .group_scans = members.size(),
                           .pull = pulls[k]});
    }
    return out;
}

Expected<std::size_t> flag_pulled(SessionStore& store, const std::vector<GroupPull>& pulls) {
    std::size_t flagged = 0;
    for (const GroupPull& p : pulls) {
        if (!p.pull.pulled) continue;
        const std::string message = p.message();
        const std::string quality = nlohmann::json{{"reason", message}}.dump();
        if (auto ok = store.record_registration(
                p.seq, {.state = ScanState::kFlagged, .quality_json = quality});
            !ok)
            return fail(ok.error());
        if (auto ok = store.add_event("registration-flagged", "", message); !ok)
            return fail(ok.error());
        ++flagged;
    }
    return flagged;
}

}  // namespace anascan::acquisition
