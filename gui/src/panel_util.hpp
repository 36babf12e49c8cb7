#pragma once
/// \file
/// Small helpers shared by the panels (private to the gui module).

#include <imgui.h>

#include <chrono>
#include <cstdint>
#include <optional>
#include <string>

namespace anascan::gui::detail {

/// Flags of a panel window: fixed place and size, chosen by the layout, not by dragging.
inline constexpr ImGuiWindowFlags kPanelFlags =
    ImGuiWindowFlags_NoMove | ImGuiWindowFlags_NoResize | ImGuiWindowFlags_NoCollapse |
    ImGuiWindowFlags_NoSavedSettings;

/// The side panels and the status bar draw no background: the app clears the whole window
/// with ImGuiCol_WindowBg before drawing (see panels.hpp).
inline constexpr ImGuiWindowFlags kClearedPanelFlags = kPanelFlags | ImGuiWindowFlags_NoBackground;

/// The banner's headline: the atlas's second font (load_scaled_font adds it, 1.3× the
/// text), else the window's font scaled by 1.3 (blurrier).
inline void begin_large_text() {
    ImFontAtlas* atlas = ImGui::GetIO().Fonts;
    if (atlas->Fonts.Size > 1) {
        ImGui::PushFont(atlas->Fonts[1]);
    } else {
        ImGui::SetWindowFontScale(1.3f);
    }
}

inline void end_large_text() {
    if (ImGui::GetIO().Fonts->Fonts.Size > 1) {
        ImGui::PopFont();
    } else {
        ImGui::SetWindowFontScale(1.0f);
    }
}

/// Places the next window at (x, y) with size (w, h), pixels.
inline void place_next_window(float x, float y, float w, float h) {
    ImGui::SetNextWindowPos(ImVec2(x, y), ImGuiCond_Always);
    ImGui::SetNextWindowSize(ImVec2(w, h), ImGuiCond_Always);
}

/// Colours that keep their meaning in both themes.
inline const ImVec4 kColorGood{0.25f, 0.85f, 0.35f, 1.0f};
inline const ImVec4 kColorWarn{1.0f, 0.8f, 0.1f, 1.0f};
inline const ImVec4 kColorBad{1.0f, 0.3f, 0.25f, 1.0f};
inline const ImVec4 kColorMuted{0.6f, 0.6f, 0.6f, 1.0f};
/// A scan placed apart from every other (unjoined): neither good nor failed.
inline const ImVec4 kColorApart{0.35f, 0.7f, 1.0f, 1.0f};

/// "12.3" or "-" for an absent figure.
std::string format_optional(const std::optional<double>& value, const char* format);

/// "14:03:27" (local time).
std::string format_clock(std::chrono::system_clock::time_point time);

/// "12.3 GB" / "850 MB".
std::string format_bytes(std::uint64_t bytes);

}  // namespace anascan::gui::detail
