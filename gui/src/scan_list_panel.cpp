#include <fmt/format.h>

#include <algorithm>
#include <string>
#include <string_view>
#include <vector>

#include "anascan/gui/panels.hpp"
#include "panel_util.hpp"

namespace anascan::gui {
namespace {

ImVec4 state_color(ScanRowState state) {
    switch (state) {
        case ScanRowState::kRegistered:
            return detail::kColorGood;
        case ScanRowState::kUnjoined:
            return detail::kColorApart;
        case ScanRowState::kFailed:
        case ScanRowState::kFlagged:
            return detail::kColorBad;
        case ScanRowState::kQueued:
            return detail::kColorWarn;
        case ScanRowState::kExcluded:
            return detail::kColorMuted;
    }
    return detail::kColorMuted;
}

/// One table row; clicking anywhere on it selects the scan. The device column only when
/// the scans come from more than one device.
void draw_row(const ScanRow& row, bool selected, bool device_column, UiActions& actions) {
    ImGui::TableNextRow();
    ImGui::TableNextColumn();
    const std::string label = fmt::format("{}##scan{}", row.seq, row.seq);
    if (ImGui::Selectable(label.c_str(), selected, ImGuiSelectableFlags_SpanAllColumns)) {
        actions.push_back({.kind = UiActionKind::kSelectScan, .seq = row.seq});
    }
    if (device_column) {
        ImGui::TableNextColumn();
        ImGui::TextUnformatted(row.device_id.c_str());
    }
    ImGui::TableNextColumn();
    ImGui::TextUnformatted(detail::format_clock(row.captured_at).c_str());
    ImGui::TableNextColumn();
    ImGui::TextColored(state_color(row.state), "%s", to_string(row.state));
    if (!row.message.empty() && ImGui::IsItemHovered()) {
        ImGui::SetTooltip("%s", row.message.c_str());
    }
    ImGui::TableNextColumn();
    ImGui::TextUnformatted(detail::format_optional(row.rms_mm, "{:.2f}").c_str());
    ImGui::TableNextColumn();
    ImGui::TextUnformatted(detail::format_optional(row.overlap_percent, "{:.0f}").c_str());
    ImGui::TableNextColumn();
    if (row.group >= 0) ImGui::Text("%d", row.group);
}

/// "24 scans: 20 ok, 2 unjoined, 1 FAILED, 1 queued" (states with no scan left out).
std::string state_counts(const std::vector<ScanRow>& rows) {
    std::string text = fmt::format("{} scans", rows.size());
    const char* sep = ": ";
    for (const ScanRowState s :
         {ScanRowState::kRegistered, ScanRowState::kUnjoined, ScanRowState::kFlagged,
          ScanRowState::kFailed, ScanRowState::kQueued, ScanRowState::kExcluded}) {
        const auto n =
            std::count_if(rows.begin(), rows.end(), [&](const ScanRow& r) { return r.state == s; });
        if (n == 0) continue;
        text += fmt::format("{}{} {}", sep, n, to_string(s));
        sep = ", ";
    }
    return text;
}

/// The device, once, when every scan comes from it (its name whole); empty otherwise.
std::string single_device(const std::vector<ScanRow>& rows) {
    if (rows.empty()) return {};
    for (const ScanRow& row : rows)
        if (row.device_id != rows.front().device_id) return {};
    return rows.front().device_id;
}

/// The newest scan's line, above the list: always in sight, however the list is scrolled.
void draw_newest(const std::vector<ScanRow>& rows) {
    if (rows.empty()) return;
    const ScanRow& newest = rows.back();
    ImGui::TextUnformatted(fmt::format("Newest: scan {}", newest.seq).c_str());
    ImGui::SameLine();
    ImGui::TextColored(state_color(newest.state), "%s", to_string(newest.state));
    if (newest.rms_mm) {
        ImGui::SameLine();
        ImGui::TextUnformatted(fmt::format("RMS {:.2f} mm", *newest.rms_mm).c_str());
    }
}

void draw_table(const FieldViewState& state, bool device_column, UiActions& actions) {
    constexpr ImGuiTableFlags kFlags = ImGuiTableFlags_RowBg | ImGuiTableFlags_BordersInnerV |
                                       ImGuiTableFlags_ScrollY | ImGuiTableFlags_ScrollX |
                                       ImGuiTableFlags_SizingFixedFit;
    if (!ImGui::BeginTable("scan_table", device_column ? 7 : 6, kFlags)) return;
    ImGui::TableSetupScrollFreeze(1, 1);
    // Every column as wide as its widest entry: names are never cut (the table scrolls).
    for (const char* name : {"#", "Device", "Time", "State", "RMS", "Ovl", "Grp"}) {
        if (device_column || std::string_view(name) != "Device") ImGui::TableSetupColumn(name);
    }
    ImGui::TableHeadersRow();
    for (const ScanRow& row : state.scans) {
        draw_row(row, row.seq == state.selected_seq, device_column, actions);
    }
    // Stick to the newest scan while the list is scrolled to the bottom (as ImGui's console
    // example); scrolling up to look at older scans stays put. The target is clamped to
    // the bottom of the content when the next frame begins, new rows included.
    constexpr float kBottom = 1e9f;
    if (ImGui::GetScrollY() >= ImGui::GetScrollMaxY() - 1.0f) ImGui::SetScrollY(kBottom);
    ImGui::EndTable();
}

/// Exclude / include / re-register for the selected scan.
void draw_selected_actions(const ScanRow& row, UiActions& actions) {
    ImGui::Text("Scan %lld:", static_cast<long long>(row.seq));
    ImGui::SameLine();
    if (row.state == ScanRowState::kExcluded) {
        if (ImGui::Button("Include"))
            actions.push_back({.kind = UiActionKind::kInclude, .seq = row.seq});
    } else if (ImGui::Button("Exclude")) {
        actions.push_back({.kind = UiActionKind::kExclude, .seq = row.seq});
    }
    ImGui::SameLine();
    if (ImGui::Button("Re-register")) {
        actions.push_back({.kind = UiActionKind::kReRegister, .seq = row.seq});
    }
}

}  // namespace

void draw_scan_list(const FieldViewState& state, const PanelLayout& layout, UiActions& actions) {
    detail::place_next_window(0.0f, 0.0f, layout.scan_list_width_px,
                              layout.height_px - layout.status_height_px);
    ImGui::Begin("Scans", nullptr, detail::kClearedPanelFlags);
    const ScanRow* selected = nullptr;
    for (const ScanRow& row : state.scans) {
        if (row.seq == state.selected_seq) selected = &row;
    }
    if (selected != nullptr) {
        draw_selected_actions(*selected, actions);
    } else {
        ImGui::TextColored(detail::kColorMuted, "Click a scan to select it");
    }
    ImGui::TextWrapped("%s", state_counts(state.scans).c_str());
    const std::string device = single_device(state.scans);
    if (!device.empty()) ImGui::TextWrapped("Device %s", device.c_str());
    draw_newest(state.scans);
    ImGui::TextColored(detail::kColorMuted, "RMS in mm, overlap (Ovl) in %%");
    draw_table(state, device.empty() && !state.scans.empty(), actions);
    ImGui::End();
}

}  // namespace anascan::gui
