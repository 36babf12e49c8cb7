// The device panel's settings (editable, with units and ranges) and its live camera preview.
#include <fmt/format.h>

#include <algorithm>
#include <cmath>

#include "anascan/gui/panels.hpp"
#include "panel_util.hpp"

namespace anascan::gui {

using acquisition::DeviceSetting;
using acquisition::DeviceSettingKind;

std::string setting_problem(const DeviceSetting& s) {
    if (s.kind == DeviceSettingKind::kChoice) {
        if (s.choice >= 0 && s.choice < static_cast<int>(s.choices.size())) return {};
        return fmt::format("{}: choose one of the {} offered", s.label, s.choices.size());
    }
    const std::string unit = s.unit.empty() ? "" : " " + s.unit;
    if (!std::isfinite(s.value)) return fmt::format("{} is not a number", s.label);
    if (s.value >= s.min && s.value <= s.max) return {};
    return fmt::format("{} {:g}{} is outside {:g}-{:g}{}", s.label, s.value, unit, s.min, s.max,
                       unit);
}

namespace {

/// +/- step of a number field: a round tenth of a twentieth of the range, at least 1e-3.
double step_of(const DeviceSetting& s) {
    const double span = std::max(s.max - s.min, 1e-3);
    return std::max(1e-3, std::pow(10.0, std::floor(std::log10(span / 20.0))));
}

/// One setting: its widget, its unit and range, and in red why its value is not allowed.
/// Returns whether the value is allowed.
bool draw_setting(const DeviceSetting& s, int index, UiActions& actions) {
    const std::string id = fmt::format("##setting{}", index);
    ImGui::TextUnformatted(s.label.c_str());
    if (s.kind == DeviceSettingKind::kNumber) {
        ImGui::SameLine();
        ImGui::TextColored(detail::kColorMuted, "(%g-%g %s)", s.min, s.max, s.unit.c_str());
        double value = s.value;
        ImGui::SetNextItemWidth(ImGui::GetContentRegionAvail().x * 0.75f);
        const double step = step_of(s);
        if (ImGui::InputDouble(id.c_str(), &value, step, 10.0 * step, "%.6g"))
            actions.push_back(
                {.kind = UiActionKind::kEditSetting, .setting_index = index, .value = value});
        ImGui::SameLine();
        ImGui::TextUnformatted(s.unit.c_str());
    } else {
        const char* current = s.choice >= 0 && s.choice < static_cast<int>(s.choices.size())
                                  ? s.choices[static_cast<std::size_t>(s.choice)].c_str()
                                  : "-";
        if (ImGui::BeginCombo(id.c_str(), current)) {
            for (int c = 0; c < static_cast<int>(s.choices.size()); ++c)
                if (ImGui::Selectable(s.choices[static_cast<std::size_t>(c)].c_str(),
                                      c == s.choice))
                    actions.push_back({.kind = UiActionKind::kEditSetting,
                                       .setting_index = index,
                                       .value = static_cast<double>(c)});
            ImGui::EndCombo();
        }
    }
    const std::string problem = setting_problem(s);
    if (!problem.empty()) ImGui::TextColored(detail::kColorBad, "%s", problem.c_str());
    return problem.empty();
}

}  // namespace

void draw_device_settings(const DevicePanelState& device, UiActions& actions) {
    const DeviceSettingsState& st = device.settings;
    if (!device.connected && st.applied.settings.empty()) {
        ImGui::BeginDisabled(device.active_device < 0 || st.busy);
        if (ImGui::Button(st.busy ? "Connecting..." : "Connect: settings, camera view",
                          ImVec2(ImGui::GetContentRegionAvail().x, 0.0f)))
            actions.push_back({.kind = UiActionKind::kOpenDevice});
        ImGui::EndDisabled();
    } else if (st.edited.settings.empty()) {
        ImGui::TextColored(detail::kColorMuted, st.busy ? "Reading the device's settings..."
                                                        : "The device has no settings");
    } else {
        ImGui::TextUnformatted("Device settings");
        bool all_valid = true;
        for (int i = 0; i < static_cast<int>(st.edited.settings.size()); ++i)
            all_valid = draw_setting(st.edited.settings[static_cast<std::size_t>(i)], i, actions) &&
                        all_valid;
        const bool changed = st.edited != st.applied;
        ImGui::BeginDisabled(!changed || !all_valid || st.busy || device.capturing);
        if (ImGui::Button(st.busy ? "Applying..." : "Apply settings"))
            actions.push_back({.kind = UiActionKind::kApplySettings});
        ImGui::EndDisabled();
        ImGui::SameLine();
        ImGui::BeginDisabled(!changed);
        if (ImGui::Button("Revert")) actions.push_back({.kind = UiActionKind::kRevertSettings});
        ImGui::EndDisabled();
    }
    if (!st.message.empty())
        ImGui::TextColored(st.message_is_error ? detail::kColorBad : detail::kColorGood, "%s",
                           st.message.c_str());
}

void draw_camera_preview(const DevicePanelState& device) {
    if (device.cameras.empty()) {
        if (!device.cameras_caption.empty())
            ImGui::TextColored(detail::kColorMuted, "%s", device.cameras_caption.c_str());
        return;
    }
    // Side by side, together as wide as the panel, in a child window ("Cameras": the app
    // finds its rectangle for the state dump).
    const float avail = ImGui::GetContentRegionAvail().x;
    const float each =
        (avail - ImGui::GetStyle().ItemSpacing.x) / static_cast<float>(device.cameras.size());
    float tallest = 0.0f;
    for (const CameraPreviewView& cam : device.cameras)
        tallest = std::max(tallest, cam.width_px > 0 ? each * static_cast<float>(cam.height_px) /
                                                           static_cast<float>(cam.width_px)
                                                     : 0.75f * each);
    ImGui::BeginChild(kCameraPreviewChild, ImVec2(avail, tallest), false,
                      ImGuiWindowFlags_NoBackground | ImGuiWindowFlags_NoScrollbar);
    for (std::size_t i = 0; i < device.cameras.size(); ++i) {
        const CameraPreviewView& cam = device.cameras[i];
        if (i > 0) ImGui::SameLine();
        const float aspect =
            cam.width_px > 0 ? static_cast<float>(cam.height_px) / static_cast<float>(cam.width_px)
                             : 0.75f;
        ImGui::Image(reinterpret_cast<ImTextureID>(cam.texture), ImVec2(each, each * aspect));
    }
    ImGui::EndChild();
    ImGui::TextColored(detail::kColorMuted, "%s", device.cameras_caption.c_str());
}

}  // namespace anascan::gui
