// The device panel's settings and camera preview in a headless ImGui context: the form is
// drawn from explicit state, edits and "Apply" come back as actions, an out-of-range value
// is named in red and cannot be applied, the cameras are drawn side by side.
#include <gtest/gtest.h>

#include <algorithm>
#include <limits>
#include <string_view>

#include "anascan/gui/panels.hpp"
#include "headless_imgui.hpp"

namespace anascan::gui {
namespace {

constexpr PanelLayout kLayout{};

acquisition::DeviceSettingsForm sl_form() {
    return {.device = "sim:structured-light/small-block",
            .settings = {{.key = "exposure_us",
                          .label = "Exposure",
                          .unit = "µs",
                          .min = 1000.0,
                          .max = 40000.0,
                          .value = 10000.0},
                         {.key = "max_range_m",
                          .label = "Farthest depth",
                          .unit = "m",
                          .min = 0.3,
                          .max = 5.0,
                          .value = 3.0}}};
}

FieldViewState connected_device() {
    FieldViewState state;
    state.device.devices = {{.id = "sim:structured-light/small-block",
                             .kind = "structured light",
                             .connected = true,
                             .status = "ready"}};
    state.device.active_device = 0;
    state.device.connected = true;
    state.device.settings.applied = state.device.settings.edited = sl_form();
    return state;
}

/// Every action of clicks down the device panel (left part, where the buttons start).
UiActions sweep_device_panel(HeadlessImGui& ui, const FieldViewState& state) {
    const float x = kLayout.width_px - kLayout.device_width_px + 30.0f;
    UiActions warmup, all;
    ui.frame([&] { draw_field_panels(state, kLayout, warmup); });
    for (float y = 0.0f; y < kLayout.height_px - kLayout.status_height_px; y += 3.0f) {
        UiActions actions;
        ui.click([&] { draw_field_panels(state, kLayout, actions); }, ImVec2(x, y));
        all.insert(all.end(), actions.begin(), actions.end());
    }
    return all;
}

std::size_t count(const UiActions& actions, UiActionKind kind) {
    return static_cast<std::size_t>(std::count_if(
        actions.begin(), actions.end(), [&](const UiAction& a) { return a.kind == kind; }));
}

TEST(DeviceSettings, AProblemNamesTheSettingTheValueAndTheAllowedRangeWithUnits) {
    acquisition::DeviceSetting exposure = sl_form().settings[0];
    EXPECT_EQ(setting_problem(exposure), "");
    exposure.value = 50000.0;
    EXPECT_EQ(setting_problem(exposure), "Exposure 50000 µs is outside 1000-40000 µs");
    exposure.value = std::numeric_limits<double>::quiet_NaN();
    EXPECT_EQ(setting_problem(exposure), "Exposure is not a number");
    const acquisition::DeviceSetting stream{.key = "profile",
                                            .label = "Stream",
                                            .kind = acquisition::DeviceSettingKind::kChoice,
                                            .choices = {"640 x 480 grey8"},
                                            .choice = 3};
    EXPECT_NE(setting_problem(stream).find("Stream"), std::string::npos);
}

TEST(DeviceSettings, EditsChangeOnlyTheEditedFormAndRevertRestoresIt) {
    FieldViewState state = connected_device();
    EXPECT_TRUE(apply_view_action(
        state, {.kind = UiActionKind::kEditSetting, .setting_index = 0, .value = 20000.0}));
    EXPECT_DOUBLE_EQ(state.device.settings.edited.settings[0].value, 20000.0);
    EXPECT_DOUBLE_EQ(state.device.settings.applied.settings[0].value, 10000.0);
    EXPECT_TRUE(apply_view_action(
        state, {.kind = UiActionKind::kEditSetting, .setting_index = 7, .value = 1.0}))
        << "an index out of the form is ignored";
    EXPECT_TRUE(apply_view_action(state, {.kind = UiActionKind::kRevertSettings}));
    EXPECT_EQ(state.device.settings.edited, state.device.settings.applied);
    EXPECT_FALSE(apply_view_action(state, {.kind = UiActionKind::kApplySettings}))
        << "applying goes to the session";
}

TEST(DeviceSettings, ApplyOnlyWithAValidChange) {
    HeadlessImGui ui;
    FieldViewState state = connected_device();
    EXPECT_EQ(count(sweep_device_panel(ui, state), UiActionKind::kApplySettings), 0u)
        << "nothing changed: nothing to apply";
    state.device.settings.edited.settings[0].value = 20000.0;
    EXPECT_GT(count(sweep_device_panel(ui, state), UiActionKind::kApplySettings), 0u);
    state.device.settings.edited.settings[0].value = 50000.0;  // outside [1000, 40000]
    EXPECT_EQ(count(sweep_device_panel(ui, state), UiActionKind::kApplySettings), 0u);
    state.device.settings.edited.settings[0].value = 20000.0;
    state.device.capturing = true;  // not while a capture runs
    EXPECT_EQ(count(sweep_device_panel(ui, state), UiActionKind::kApplySettings), 0u);
}

TEST(DeviceSettings, ConnectUntilTheDeviceIsAttached) {
    HeadlessImGui ui;
    FieldViewState state = connected_device();
    state.device.connected = false;
    state.device.settings = {};
    EXPECT_GT(count(sweep_device_panel(ui, state), UiActionKind::kOpenDevice), 0u);
    state.device.connected = true;
    EXPECT_EQ(count(sweep_device_panel(ui, state), UiActionKind::kOpenDevice), 0u);
}

TEST(CameraPreview, BothCamerasSideBySideInTheirChildWindow) {
    HeadlessImGui ui;
    FieldViewState state = connected_device();
    auto child = [&]() -> const ImGuiWindow* {
        UiActions actions;
        ui.frame([&] { draw_field_panels(state, kLayout, actions); });
        ui.frame([&] { draw_field_panels(state, kLayout, actions); });
        for (const ImGuiWindow* w : ImGui::GetCurrentContext()->Windows)
            if (w->WasActive &&
                std::string_view(w->Name).find("/Cameras_") != std::string_view::npos)
                return w;
        return nullptr;
    };
    EXPECT_EQ(child(), nullptr) << "no images: no preview";
    state.device.cameras = {{.texture = 1, .width_px = 160, .height_px = 120, .name = "cam1"},
                            {.texture = 2, .width_px = 160, .height_px = 120, .name = "cam2"}};
    state.device.cameras_caption = "Cameras at 12:00:00";
    const ImGuiWindow* w = child();
    ASSERT_NE(w, nullptr);
    EXPECT_GE(w->Pos.x, kLayout.width_px - kLayout.device_width_px) << "inside the device panel";
    // Two 4:3 images side by side: the child is about 3/8 as high as it is wide.
    EXPECT_NEAR(w->Size.y / w->Size.x, 0.375f, 0.05f);
}

}  // namespace
}  // namespace anascan::gui
