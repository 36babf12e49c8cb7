#include "headless_driver.hpp"

#include <imgui.h>

#include <cstdio>
#include <utility>

#include "app_state.hpp"
#include "field_window.hpp"
#include "headless_device.hpp"
#include "screenshot.hpp"
#include "session_link.hpp"

namespace anascan::field {

HeadlessDriver::HeadlessDriver(const HeadlessConfig& config, const AppState& app)
    : config_(config) {
    if (app.link && headless())
        phase_ = config.capture_views > 0 ? Phase::kCapturing : Phase::kSettling;
}

double HeadlessDriver::idle_wait_s(bool view_complete) const {
    const bool idle = (!headless() || !counting()) && view_complete && !ImGui::IsAnyMouseDown();
    return idle ? 0.05 : 0.0;
}

void HeadlessDriver::step(AppState& app, gui::UiActions& actions) {
    app.camera.orbit(config_.orbit_px_per_frame, 0.0);
    if (app.link) phase_ = drive_session(app, actions);
}

/// Device panel steps once settled: "Connect", then the settings typed and applied; true
/// when one was taken (the session then settles again).
bool HeadlessDriver::device_steps(AppState& app, gui::UiActions& actions) {
    if (config_.connect_device && !std::exchange(connect_sent_, true)) {
        actions.push_back({.kind = gui::UiActionKind::kOpenDevice});
        return true;
    }
    if (config_.apply_settings.empty() || std::exchange(settings_sent_, true)) return false;
    auto steps = setting_actions(app.view.device.settings, config_.apply_settings);
    if (!steps) {
        app.view.device.settings.message = "Not applied: " + steps.error().message;
        app.view.device.settings.message_is_error = true;
        std::fprintf(stderr, "anascan-field: error: %s\n", steps.error().message.c_str());
        return false;
    }
    actions.insert(actions.end(), steps->begin(), steps->end());
    return true;
}

/// The capture action whenever no capture runs, until `capture_views` captures have
/// finished; then wait for registration and the view.
HeadlessDriver::Phase HeadlessDriver::drive_session(AppState& app, gui::UiActions& actions) {
    SessionLink& link = *app.link;
    switch (phase_) {
        case Phase::kCapturing:
            if (link.captures_finished() >= config_.capture_views) {
                link.request_idle();
                return Phase::kSettling;
            }
            if (!link.capturing()) actions.push_back({.kind = gui::UiActionKind::kCapture});
            return phase_;
        case Phase::kReregistering:  // the action was applied in the last frame
            link.request_idle();
            return Phase::kSettling;
        case Phase::kSettling:
            break;
        case Phase::kCounting:
            return phase_;
    }
    if (!link.settled()) return phase_;
    if (device_steps(app, actions)) return Phase::kSettling;  // then settle again
    if (config_.reregister_seq > 0 && !std::exchange(reregister_sent_, true)) {
        actions.push_back({.kind = gui::UiActionKind::kReRegister, .seq = config_.reregister_seq});
        return Phase::kReregistering;
    }
    if (config_.make_mesh && !std::exchange(mesh_sent_, true)) {
        actions.push_back({.kind = gui::UiActionKind::kMakeMesh});
        return Phase::kSettling;  // settled again once the mesh is made (or failed)
    }
    app.fit_pending = true;  // the whole model in the screenshot
    return Phase::kCounting;
}

Expected<void> HeadlessDriver::after_draw(const FieldWindow& window) const {
    if (!config_.screenshot_png || !counting() || counted_ + 1 != config_.frames) return {};
    int fb_w = 0, fb_h = 0;
    window.framebuffer_size(fb_w, fb_h);
    return write_screenshot(*config_.screenshot_png, fb_w, fb_h);
}

Expected<void> HeadlessDriver::end_frame() {
    if (counting()) {
        ++counted_;
        return {};
    }
    if (started_.seconds() <= config_.session_timeout_s) return {};
    char text[160];
    std::snprintf(text, sizeof(text),
                  "the session did not settle within %.0f s (captures or registration still "
                  "running)",
                  config_.session_timeout_s);
    return fail(ErrorCode::kTimeout, text);
}

}  // namespace anascan::field
