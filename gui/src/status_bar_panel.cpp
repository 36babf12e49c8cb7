#include "anascan/gui/panels.hpp"
#include "panel_util.hpp"

namespace anascan::gui {

void draw_status_bar(const FieldViewState& state, const PanelLayout& layout) {
    detail::place_next_window(0.0f, layout.height_px - layout.status_height_px, layout.width_px,
                              layout.status_height_px);
    ImGui::Begin("Status", nullptr, detail::kClearedPanelFlags | ImGuiWindowFlags_NoTitleBar);
    const StatusBarState& status = state.status;
    ImGui::Text("Coverage %s %%",
                detail::format_optional(status.coverage_percent, "{:.1f}").c_str());
    ImGui::SameLine(0.0f, 30.0f);
    ImGui::TextColored(status.queued_registrations > 0 ? detail::kColorWarn : detail::kColorGood,
                       "Queued registrations %d", status.queued_registrations);
    ImGui::SameLine(0.0f, 30.0f);
    if (status.disk_free_bytes) {
        const bool low = *status.disk_free_bytes < 2'000'000'000ull;  // a few hundred scans
        ImGui::TextColored(low ? detail::kColorBad : detail::kColorGood, "Disk %s free",
                           detail::format_bytes(*status.disk_free_bytes).c_str());
    } else {
        ImGui::TextUnformatted("Disk -");
    }
    ImGui::SameLine(0.0f, 30.0f);
    if (status.last_error.empty()) {
        ImGui::TextColored(detail::kColorMuted, "No errors");
    } else {
        ImGui::TextColored(detail::kColorBad, "Error: %s", status.last_error.c_str());
    }
    ImGui::End();
}

}  // namespace anascan::gui
