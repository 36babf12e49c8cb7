#include "panel_util.hpp"

#include <fmt/format.h>

#include <ctime>

#include "anascan/gui/panels.hpp"

namespace anascan::gui::detail {

std::string format_optional(const std::optional<double>& value, const char* format) {
    if (!value) return "-";
    return fmt::format(fmt::runtime(format), *value);
}

std::string format_clock(std::chrono::system_clock::time_point time) {
    const std::time_t t = std::chrono::system_clock::to_time_t(time);
    std::tm local{};
    localtime_r(&t, &local);
    return fmt::format("{:02}:{:02}:{:02}", local.tm_hour, local.tm_min, local.tm_sec);
}

std::string format_bytes(std::uint64_t bytes) {
    const double gb = static_cast<double>(bytes) / 1e9;
    if (gb >= 1.0) return fmt::format("{:.1f} GB", gb);
    return fmt::format("{:.0f} MB", static_cast<double>(bytes) / 1e6);
}

}  // namespace anascan::gui::detail

namespace anascan::gui {

PanelBackground panel_background() {
    const ImVec4 c = ImGui::GetStyle().Colors[ImGuiCol_WindowBg];
    return {.r = c.x * c.w, .g = c.y * c.w, .b = c.z * c.w};
}

}  // namespace anascan::gui
