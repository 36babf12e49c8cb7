#include <fmt/format.h>

#include "anascan/gui/panels.hpp"
#include "panel_util.hpp"

namespace anascan::gui {

bool draw_failure_banner(const FieldViewState& state, const PanelLayout& layout,
                         UiActions& actions) {
    const std::optional<FailureBanner> banner = failure_banner(state);
    if (!banner) return false;
    detail::place_next_window(layout.view_x_px(), 0.0f, layout.view_width_px(),
                              layout.banner_height_px);
    ImGui::PushStyleColor(ImGuiCol_WindowBg, ImVec4(0.75f, 0.05f, 0.05f, 1.0f));
    ImGui::PushStyleColor(ImGuiCol_Text, ImVec4(1.0f, 1.0f, 1.0f, 1.0f));
    ImGui::Begin("Registration failed", nullptr, detail::kPanelFlags | ImGuiWindowFlags_NoTitleBar);
    ImGui::SetWindowFontScale(1.3f);
    ImGui::TextWrapped("%s", banner->message.c_str());
    ImGui::SetWindowFontScale(1.0f);
    ImGui::TextWrapped("Try: %s", banner->what_to_try.c_str());
    const std::string label = fmt::format("Exclude scan {}  (X)", banner->seq);
    if (ImGui::Button(label.c_str())) {
        actions.push_back({.kind = UiActionKind::kExclude, .seq = banner->seq});
    }
    ImGui::End();
    ImGui::PopStyleColor(2);
    return true;
}

}  // namespace anascan::gui
