#include <fmt/format.h>

#include "anascan/gui/panels.hpp"
#include "panel_util.hpp"

namespace anascan::gui {
namespace {

const char* window_name(BannerKind kind) {
    switch (kind) {
        case BannerKind::kCaptureFailed:
            return "Capture failed";
        case BannerKind::kFailed:
            return "Registration failed";
        case BannerKind::kSplit:
            return "Model split";
        case BannerKind::kDisagree:
            return "Scans disagree";
    }
    return "Banner";
}

}  // namespace

bool draw_failure_banner(const FieldViewState& state, const PanelLayout& layout,
                         UiActions& actions) {
    const std::optional<FailureBanner> banner = session_banner(state);
    if (!banner) return false;
    const bool failed = banner->kind != BannerKind::kSplit;
    // Height 0: as high as its text (at least banner_height_px).
    detail::place_next_window(layout.view_x_px(), 0.0f, layout.view_width_px(), 0.0f);
    ImGui::SetNextWindowSizeConstraints(ImVec2(0.0f, layout.banner_height_px),
                                        ImVec2(layout.width_px, layout.height_px));
    // Red for a failure, dark amber for a split model; white text on both (bright light).
    ImGui::PushStyleColor(ImGuiCol_WindowBg, failed ? ImVec4(0.75f, 0.05f, 0.05f, 1.0f)
                                                    : ImVec4(0.72f, 0.36f, 0.0f, 1.0f));
    ImGui::PushStyleColor(ImGuiCol_Text, ImVec4(1.0f, 1.0f, 1.0f, 1.0f));
    ImGui::Begin(window_name(banner->kind), nullptr,
                 detail::kPanelFlags | ImGuiWindowFlags_NoTitleBar);
    detail::begin_large_text();
    ImGui::TextWrapped("%s", banner->message.c_str());
    detail::end_large_text();
    if (!banner->details.empty()) ImGui::TextWrapped("%s", banner->details.c_str());
    ImGui::TextWrapped("Try: %s", banner->what_to_try.c_str());
    if (banner->seq >= 0) {
        const std::string label = banner->kind == BannerKind::kFailed
                                      ? fmt::format("Exclude scan {}  (X)", banner->seq)
                                      : fmt::format("Exclude scan {}", banner->seq);
        if (ImGui::Button(label.c_str())) {
            actions.push_back({.kind = UiActionKind::kExclude, .seq = banner->seq});
        }
    }
    ImGui::End();
    ImGui::PopStyleColor(2);
    return true;
}

}  // namespace anascan::gui
