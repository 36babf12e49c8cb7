#include <fmt/format.h>

#include <string_view>

#include "anascan/gui/panels.hpp"
#include "panel_util.hpp"

namespace anascan::gui {
namespace {

ImVec4 state_color(ScanRowState state) {
    switch (state) {
        case ScanRowState::kRegistered:
            return detail::kColorGood;
        case ScanRowState::kFailed:
            return detail::kColorBad;
        case ScanRowState::kQueued:
            return detail::kColorWarn;
        case ScanRowState::kExcluded:
            return detail::kColorMuted;
    }
    return detail::kColorMuted;
}

/// One table row; clicking anywhere on it selects the scan.
void draw_row(const ScanRow& row, bool selected, UiActions& actions) {
    ImGui::TableNextRow();
    ImGui::TableNextColumn();
    const std::string label = fmt::format("{}##scan{}", row.seq, row.seq);
    if (ImGui::Selectable(label.c_str(), selected, ImGuiSelectableFlags_SpanAllColumns)) {
        actions.push_back({.kind = UiActionKind::kSelectScan, .seq = row.seq});
    }
    ImGui::TableNextColumn();
    ImGui::TextUnformatted(row.device_id.c_str());
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
        ImGui::TextColored(detail::kColorMuted, "%zu scans; click one to select",
                           state.scans.size());
    }
    ImGui::TextColored(detail::kColorMuted, "RMS in mm, overlap (Ovl) in %%");
    constexpr ImGuiTableFlags kFlags = ImGuiTableFlags_RowBg | ImGuiTableFlags_BordersInnerV |
                                       ImGuiTableFlags_ScrollY | ImGuiTableFlags_SizingFixedFit;
    if (ImGui::BeginTable("scan_table", 7, kFlags)) {
        ImGui::TableSetupScrollFreeze(0, 1);
        // The device column takes what is left; the figures keep their full width.
        for (const char* name : {"#", "Device", "Time", "State", "RMS", "Ovl", "Grp"}) {
            const bool device = std::string_view(name) == "Device";
            ImGui::TableSetupColumn(name, device ? ImGuiTableColumnFlags_WidthStretch
                                                 : ImGuiTableColumnFlags_WidthFixed);
        }
        ImGui::TableHeadersRow();
        for (const ScanRow& row : state.scans) {
            draw_row(row, row.seq == state.selected_seq, actions);
        }
        // Stick to the newest scan while the list is scrolled to the bottom (as ImGui's
        // console example); scrolling up to look at older scans stays put.
        if (ImGui::GetScrollY() >= ImGui::GetScrollMaxY()) ImGui::SetScrollHereY(1.0f);
        ImGui::EndTable();
    }
    ImGui::End();
}

}  // namespace anascan::gui
