#include "anascan/gui/theme.hpp"

#include <imgui.h>

#include <filesystem>

namespace anascan::gui {
namespace {

constexpr const char* kFontPath = "/usr/share/fonts/truetype/dejavu/DejaVuSans.ttf";
constexpr float kBaseFontPx = 15.0f;
constexpr float kLargeFontFactor = 1.3f;

/// White-on-black text, bright frames and yellow accents: readable in sunlight on a
/// glossy laptop screen.
void set_high_contrast_colors(ImGuiStyle& style) {
    ImGui::StyleColorsDark(&style);
    ImVec4* c = style.Colors;
    const ImVec4 black(0.0f, 0.0f, 0.0f, 1.0f);
    const ImVec4 white(1.0f, 1.0f, 1.0f, 1.0f);
    const ImVec4 yellow(1.0f, 0.9f, 0.0f, 1.0f);
    c[ImGuiCol_Text] = white;
    c[ImGuiCol_WindowBg] = black;
    c[ImGuiCol_ChildBg] = black;
    c[ImGuiCol_PopupBg] = black;
    c[ImGuiCol_Border] = white;
    c[ImGuiCol_TitleBg] = ImVec4(0.15f, 0.15f, 0.15f, 1.0f);
    c[ImGuiCol_TitleBgActive] = ImVec4(0.25f, 0.25f, 0.25f, 1.0f);
    c[ImGuiCol_FrameBg] = ImVec4(0.2f, 0.2f, 0.2f, 1.0f);
    c[ImGuiCol_Button] = ImVec4(0.1f, 0.3f, 0.8f, 1.0f);
    c[ImGuiCol_ButtonHovered] = ImVec4(0.2f, 0.45f, 1.0f, 1.0f);
    c[ImGuiCol_ButtonActive] = yellow;
    c[ImGuiCol_Header] = ImVec4(0.1f, 0.3f, 0.8f, 1.0f);
    c[ImGuiCol_HeaderHovered] = ImVec4(0.2f, 0.45f, 1.0f, 1.0f);
    c[ImGuiCol_HeaderActive] = yellow;
    c[ImGuiCol_CheckMark] = yellow;
    c[ImGuiCol_TableRowBg] = black;
    c[ImGuiCol_TableRowBgAlt] = ImVec4(0.12f, 0.12f, 0.12f, 1.0f);
    style.FrameBorderSize = 1.0f;
    style.WindowBorderSize = 2.0f;
}

}  // namespace

void apply_theme(const ThemeConfig& config, bool font_already_scaled) {
    ImGuiStyle style;  // fresh defaults: no accumulated scaling
    if (config.high_contrast) {
        set_high_contrast_colors(style);
    } else {
        ImGui::StyleColorsDark(&style);
    }
    style.WindowRounding = 0.0f;
    style.ScaleAllSizes(config.font_scale);
    ImGui::GetStyle() = style;
    ImGui::GetIO().FontGlobalScale = font_already_scaled ? 1.0f : config.font_scale;
}

bool load_scaled_font(float font_scale) {
    std::error_code ec;
    if (!std::filesystem::exists(kFontPath, ec)) return false;
    ImGuiIO& io = ImGui::GetIO();
    if (io.Fonts->AddFontFromFileTTF(kFontPath, kBaseFontPx * font_scale) == nullptr) return false;
    // The banner's headline (detail::begin_large_text): drawn at its own size, not scaled.
    io.Fonts->AddFontFromFileTTF(kFontPath, kLargeFontFactor * kBaseFontPx * font_scale);
    return true;
}

}  // namespace anascan::gui
