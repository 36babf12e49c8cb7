#include "anascan/acquisition/capture/stone_check.hpp"

#include <algorithm>
#include <nlohmann/json.hpp>
#include <vector>

#include "anascan/acquisition/store/groups.hpp"
#include "anascan/processing/core/pose.hpp"

namespace anascan::acquisition {
namespace {

/// The model's scans (largest group of the scans other than `seq`), at most `max` spread
/// evenly over the capture order.
std::vector<ScanRecord> model_scans(const std::vector<ScanRecord>& scans, std::int64_t seq,
                                    std::size_t max, int& group) {
    std::vector<ScanRecord> others;
    for (const ScanRecord& s : scans)
        if (s.seq != seq) others.push_back(s);
    group = largest_group(others);
    std::vector<ScanRecord> members;
    for (const ScanRecord& s : others)
        if (counts_in_group(s) && s.group == group) members.push_back(s);
    if (members.size() <= max || max == 0) return members;
    std::vector<ScanRecord> spread;
    for (std::size_t k = 0; k < max; ++k) spread.push_back(members[k * members.size() / max]);
    return spread;
}

/// The registrar joined `record` to scans of the session (the model or another part of the
/// stone).
bool joined_earlier_scans(const std::vector<ScanRecord>& scans, const ScanRecord& record) {
    if (!counts_in_group(record)) return false;
    return std::any_of(scans.begin(), scans.end(), [&](const ScanRecord& s) {
        return s.seq != record.seq && counts_in_group(s) && s.group == record.group;
    });
}

/// The stone-only reduced cloud of a stored scan, in its own frame.
Expected<PointCloud> stone_cloud(const SessionStore& store, const ScanRecord& record,
                                 const StoneCheckConfig& config) {
    auto scan = store.load_scan(record.seq);
    if (!scan) return fail(scan.error());
    return reduce_to_stone({.seq = record.seq,
                            .cloud = std::move(scan->cloud),
                            .sensor_origin_scan_m = record.sensor_origin_scan_m},
                           config.registration);
}

/// Why the registrar took `record` out of its group, when it did because the fit grossly
/// contradicts the scans it was fitted onto: its points in space their sensors saw empty,
/// its surface crossing theirs or meeting it at a large angle (the pair test it failed,
/// stored as "disagreement"). A surface a fraction of a millimetre off theirs ("surfaces
/// apart") is a fit of the stone that slid, not evidence of another object: the same stone
/// seen again was taken out so on both tour seeds measured. Empty otherwise, also for
/// scans flagged by other checks (the union pull) or before the test was stored.
std::string contradiction_of(const ScanRecord& record) {
    if (record.state != ScanState::kFlagged || record.excluded) return {};
    const nlohmann::json quality = nlohmann::json::parse(record.quality_json, nullptr, false);
    const auto text = [&](const char* key) {
        return quality.is_object() && quality.contains(key) && quality[key].is_string()
                   ? quality[key].get<std::string>()
                   : std::string();
    };
    const std::string disagreement = text("disagreement");
    if (disagreement != "free space" && disagreement != "normals cross" && disagreement != "angle")
        return {};
    const std::string reason = text("reason");
    return reason.empty() ? disagreement : reason;
}

std::string outcome_message(const StoneCheck& check) {
    const std::string scan = "scan " + std::to_string(check.seq);
    switch (check.outcome) {
        case StoneCheckOutcome::kNoModel:
            return scan + ": no model yet to compare with";
        case StoneCheckOutcome::kJoined:
            return scan + " joined the stone's model";
        case StoneCheckOutcome::kLooksSame:
            return scan +
                   " joined no part of the stone's model yet; nothing in its size or surface "
                   "says another object (the stone's other side?): it stays its own group (" +
                   check.evidence.reason + ")";
        case StoneCheckOutcome::kUndecided:
            return scan +
                   " joined no part of the stone's model, and the model has too few scans "
                   "(or near-duplicate views) to tell whether it shows the stone: it stays "
                   "its own group (" +
                   check.evidence.reason + ")";
        case StoneCheckOutcome::kOtherStone:
            if (!check.contradiction.empty())
                return scan +
                       " joined no part of the stone's model: the registrar fitted it onto the "
                       "stone, and the fit contradicts the stone (" +
                       check.contradiction +
                       "); another object, or a view of the stone it "
                       "could not place (" +
                       check.evidence.reason + ")";
            return scan + " joined no part of the stone's model and shows another object: " +
                   check.evidence.reason;
    }
    return scan;
}

StoneCheckOutcome outcome_of(StoneIdentityVerdict verdict) {
    switch (verdict) {
        case StoneIdentityVerdict::kOtherStone:
            return StoneCheckOutcome::kOtherStone;
        case StoneIdentityVerdict::kLooksSame:
            return StoneCheckOutcome::kLooksSame;
        case StoneIdentityVerdict::kUndecided:
            return StoneCheckOutcome::kUndecided;
    }
    return StoneCheckOutcome::kUndecided;
}

}  // namespace

const char* to_string(StoneCheckOutcome outcome) {
    switch (outcome) {
        case StoneCheckOutcome::kNoModel:
            return "no-model";
        case StoneCheckOutcome::kJoined:
            return "joined";
        case StoneCheckOutcome::kLooksSame:
            return "looks-same";
        case StoneCheckOutcome::kUndecided:
            return "undecided";
        case StoneCheckOutcome::kOtherStone:
            return "other-stone";
    }
    return "undecided";
}

Expected<StoneCheck> check_stone_of_scan(const SessionStore& store, std::int64_t seq,
                                         const StoneCheckConfig& config) {
    auto scans = store.scans();
    if (!scans) return fail(scans.error());
    auto record = store.scan(seq);
    if (!record) return fail(record.error());
    StoneCheck check{.seq = seq};
    const std::vector<ScanRecord> members =
        model_scans(*scans, seq, config.max_model_scans, check.model_group);
    if (!members.empty()) check.model_scan = members.back().seq;
    if (members.empty()) {
        check.outcome = StoneCheckOutcome::kNoModel;
    } else if (joined_earlier_scans(*scans, *record)) {
        check.outcome = StoneCheckOutcome::kJoined;
    } else {
        std::vector<PointCloud> model;
        for (const ScanRecord& member : members) {
            auto cloud = stone_cloud(store, member, config);
            if (cloud) model.push_back(transformed(*cloud, *member.pose));
        }
        auto mine = stone_cloud(store, *record, config);
        if (mine) {
            check.evidence = compare_with_stone(model, *mine, config.identity);
        } else {
            check.evidence.reason = "no stone points to compare: " + mine.error().message;
        }
        check.outcome = outcome_of(check.evidence.verdict);
        check.contradiction = contradiction_of(*record);
        if (!check.contradiction.empty()) check.outcome = StoneCheckOutcome::kOtherStone;
    }
    check.message = outcome_message(check);
    return check;
}

std::vector<std::int64_t> scans_outside_model(const std::vector<ScanRecord>& scans,
                                              std::int64_t after_seq, int model_group) {
    std::vector<std::int64_t> out;
    for (const ScanRecord& s : scans)
        if (s.seq > after_seq && !s.excluded && !(counts_in_group(s) && s.group == model_group))
            out.push_back(s.seq);
    return out;
}

Expected<StoneCheck> check_later_scan(const SessionStore& store, std::int64_t seq,
                                      std::int64_t model_seq, const StoneCheckConfig& config) {
    auto model = store.scan(model_seq);
    if (!model) return fail(model.error());
    auto record = store.scan(seq);
    if (!record) return fail(record.error());
    StoneCheck check;  // Members set one by one: GCC 12 warns on skipped designators here.
    check.seq = seq;
    check.model_group = counts_in_group(*model) ? model->group : -1;
    check.model_scan = model_seq;
    const std::string scan = "scan " + std::to_string(seq);
    if (counts_in_group(*record) && record->group == check.model_group) {
        check.outcome = StoneCheckOutcome::kJoined;
        check.message = scan + " joined the stone's model";
        return check;
    }
    if (contradiction_of(*record).empty()) {
        check.outcome = StoneCheckOutcome::kUndecided;
        check.message = scan + " joined no part of the stone's model yet";
        return check;
    }
    auto full = check_stone_of_scan(store, seq, config);
    if (full) full->model_group = check.model_group;
    return full;
}

}  // namespace anascan::acquisition
