#include <fmt/format.h>

#include <algorithm>
#include <map>

#include "anascan/acquisition/store/groups.hpp"
#include "anascan/gui/field_view_state.hpp"

namespace anascan::gui {
namespace {

/// Registered, non-excluded scans per group id (ascending seqs).
std::map<int, std::vector<std::int64_t>> registered_groups(const FieldViewState& state) {
    std::map<int, std::vector<std::int64_t>> groups;
    for (const ScanRow& row : state.scans) {
        const bool placed =
            row.state == ScanRowState::kRegistered || row.state == ScanRowState::kUnjoined;
        if (placed && row.group >= 0) groups[row.group].push_back(row.seq);
    }
    for (auto& [group, seqs] : groups) std::sort(seqs.begin(), seqs.end());
    return groups;
}

}  // namespace

std::string format_scan_list(const std::vector<std::int64_t>& seqs) {
    if (seqs.empty()) return "no scans";
    std::string out = seqs.size() == 1 ? "scan " : "scans ";
    for (std::size_t i = 0; i < seqs.size();) {
        std::size_t j = i;
        while (j + 1 < seqs.size() && seqs[j + 1] == seqs[j] + 1) ++j;
        if (i > 0) out += ", ";
        out += j == i ? fmt::format("{}", seqs[i]) : fmt::format("{}-{}", seqs[i], seqs[j]);
        i = j + 1;
    }
    return out;
}

std::optional<FailureBanner> split_banner(const FieldViewState& state) {
    const auto groups = registered_groups(state);
    if (groups.size() < 2) return std::nullopt;
    // The view's group, by the session's one largest-group rule.
    std::vector<int> member_groups;
    for (const auto& [group, seqs] : groups)
        member_groups.insert(member_groups.end(), seqs.size(), group);
    const auto shown = groups.find(acquisition::largest_group_id(member_groups));
    std::vector<std::int64_t> apart;
    for (const auto& [group, seqs] : groups)
        if (group != shown->first) apart.insert(apart.end(), seqs.begin(), seqs.end());
    std::sort(apart.begin(), apart.end());
    FailureBanner banner{.kind = BannerKind::kSplit, .seq = apart.size() == 1 ? apart[0] : -1};
    banner.message = fmt::format("The model is split in {} parts", groups.size());
    banner.details =
        fmt::format("{} not joined to the model shown ({}, group {}).", format_scan_list(apart),
                    format_scan_list(shown->second), shown->first);
    banner.what_to_try =
        "Capture a view that overlaps both parts by about half (between their viewpoints): "
        "they join as soon as a scan links them. After turning the stone over, scan its "
        "edges first.";
    if (banner.seq >= 0) banner.what_to_try += " A stray scan can be excluded.";
    return banner;
}

std::optional<FailureBanner> disagree_banner(const FieldViewState& state) {
    std::vector<std::int64_t> flagged;
    const ScanRow* first = nullptr;
    for (const ScanRow& row : state.scans) {
        if (row.state != ScanRowState::kFlagged) continue;
        flagged.push_back(row.seq);
        if (!first) first = &row;
    }
    if (flagged.empty()) return std::nullopt;
    FailureBanner banner{.kind = BannerKind::kDisagree, .seq = flagged.back()};
    banner.message = fmt::format(
        "The scans disagree: {} {} the model and {} taken out", format_scan_list(flagged),
        flagged.size() == 1 ? "contradicts" : "contradict", flagged.size() == 1 ? "was" : "were");
    banner.details = first->message;
    banner.what_to_try =
        "The model shown keeps only the scans that agree. Scan that part again from a "
        "viewpoint that overlaps the agreeing scans by about half, or register the flagged "
        "scan again (R); X excludes it.";
    return banner;
}

std::optional<FailureBanner> session_banner(const FieldViewState& state) {
    if (state.capture_problem) {
        return FailureBanner{.kind = BannerKind::kCaptureFailed,
                             .seq = -1,
                             .message = state.capture_problem->headline,
                             .details = state.capture_problem->details,
                             .what_to_try = state.capture_problem->what_to_try};
    }
    if (auto failed = failure_banner(state)) return failed;
    if (auto disagree = disagree_banner(state)) return disagree;
    return split_banner(state);
}

}  // namespace anascan::gui
