#include "anascan/gui/session_view.hpp"

#include <fmt/format.h>

#include <map>
#include <nlohmann/json.hpp>

#include "anascan/acquisition/coverage/session_coverage.hpp"
#include "anascan/processing/coverage/coverage.hpp"

namespace anascan::gui {
namespace {

ScanRowState row_state(acquisition::ScanState state) {
    switch (state) {
        case acquisition::ScanState::kQueued:
            return ScanRowState::kQueued;
        case acquisition::ScanState::kRegistered:
            return ScanRowState::kRegistered;
        case acquisition::ScanState::kFailed:
            return ScanRowState::kFailed;
        case acquisition::ScanState::kExcluded:
            return ScanRowState::kExcluded;
        case acquisition::ScanState::kFlagged:
            return ScanRowState::kFlagged;
    }
    return ScanRowState::kQueued;
}

std::optional<double> number(const nlohmann::json& object, const char* key) {
    const auto it = object.find(key);
    if (it == object.end() || !it->is_number()) return std::nullopt;
    return it->get<double>();
}

void fill_quality(const std::string& quality_json, ScanRow& row) {
    if (quality_json.empty()) return;
    const nlohmann::json q = nlohmann::json::parse(quality_json, nullptr, false);
    if (!q.is_object()) return;
    const auto method = q.find("method");
    const bool placed_unmatched =
        method != q.end() && method->is_string() && (*method == "first" || *method == "new-group");
    if (!placed_unmatched) {  // else the figures are 0 for want of a match, not measured
        if (const auto rms = number(q, "rms_m")) row.rms_mm = *rms * 1000.0;
        if (const auto overlap = number(q, "overlap_fraction"))
            row.overlap_percent = *overlap * 100.0;
    }
    for (const char* key : {"message", "reason"}) {
        const auto it = q.find(key);
        if (it != q.end() && it->is_string() && row.message.empty()) row.message = *it;
    }
}

}  // namespace

ScanRow scan_row(const acquisition::ScanRecord& record) {
    ScanRow row{
        .seq = record.seq,
        .device_id = record.device_id,
        .captured_at = record.captured_at,
        .state = row_state(record.excluded ? acquisition::ScanState::kExcluded : record.state),
        .group = record.group};
    fill_quality(record.quality_json, row);
    if (!record.file_problem.empty()) row.message = record.file + ": " + record.file_problem;
    return row;
}

void mark_unjoined(std::vector<ScanRow>& rows) {
    std::map<int, int> members;
    for (const ScanRow& row : rows)
        if (row.state == ScanRowState::kRegistered && row.group >= 0) ++members[row.group];
    for (ScanRow& row : rows)
        if (row.state == ScanRowState::kRegistered && row.group >= 0 && members[row.group] == 1)
            row.state = ScanRowState::kUnjoined;
}

StoredCoverage parse_coverage_json(std::string_view json) {
    StoredCoverage coverage;
    const Expected<CoverageSummary> summary = coverage_from_json(json);
    if (!summary) return coverage;
    coverage.fraction = summary->fraction;
    for (const CoverageHole& hole : summary->holes)
        coverage.holes.push_back(
            {.centre_m = hole.centre_m, .normal = hole.normal, .area_m2 = hole.area_m2});
    return coverage;
}

bool drawn_in_view(const acquisition::ScanRecord& record, int group) {
    return record.state == acquisition::ScanState::kRegistered && !record.excluded &&
           record.pose.has_value() && record.group == group && group >= 0;
}

int model_group(const std::vector<acquisition::ScanRecord>& scans) {
    return acquisition::largest_group(scans);  // the group coverage is measured on
}

std::string check_summary(const acquisition::SessionCheckReport& report) {
    if (report.issues.empty() && report.integrity == "ok") return {};
    std::string text = fmt::format("Reopened: session check: {} of {} scans ok, {} finding(s)",
                                   report.scans_ok, report.scans_checked, report.issues.size());
    for (const auto& issue : report.issues) {
        text += fmt::format("; {}: {}", issue.file.filename().string(), issue.problem);
    }
    if (report.integrity != "ok") text += "; database: " + report.integrity;
    if (!report.clean()) {
        text += fmt::format("; run `anascan session check {} --repair`", report.dir.string());
    }
    return text;
}

}  // namespace anascan::gui
