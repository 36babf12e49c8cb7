#include "field_app.hpp"

#include <cstdio>

#include "anascan/gui/level_of_detail.hpp"
#include "app_state.hpp"
#include "field_window.hpp"
#include "frame_meter.hpp"
#include "session_link.hpp"
#include "state_dump.hpp"

namespace anascan::field {
namespace {

int report_error(const Error& error) {
    std::fprintf(stderr, "anascan-field: error: %s\n", error.message.c_str());
    return 1;
}

SessionLinkConfig session_link_config(const SessionOptions& options) {
    SessionLinkConfig link{.dir = *options.dir,
                           .device_uri = options.device,
                           .tour = {.views = options.tour_views,
                                    .flip_after = options.flip_after < 0 ? options.tour_views / 2
                                                                         : options.flip_after},
                           .sim_unplug_after = options.sim_unplug_after,
                           .worker_nice = options.worker_nice,
                           .upload_points_per_frame = options.upload_points_per_frame,
                           .mesh_resolution_mm = options.mesh_resolution_mm,
                           .log_events = options.log_events};
    link.settings.angular_step_deg = options.angular_step_deg;
    return link;
}

/// Init after the window: renderer, clouds, theme, session.
Expected<void> init_app(const FieldAppConfig& config, const FieldWindow& window, AppState& app) {
    if (auto created = create_renderer(app); !created) return created;
    if (auto loaded = load_scans(config.inputs, app); !loaded) return loaded;
    app.view.color_mode = config.view.color_mode;
    app.view.high_contrast = config.view.high_contrast;
    app.theme = {.high_contrast = config.view.high_contrast, .font_scale = config.view.font_scale};
    gui::apply_theme(app.theme, window.font_scaled());
    if (config.session.dir) {
        app.link = std::make_unique<SessionLink>(session_link_config(config.session));
        app.link->open(app.view);
    }
    return {};
}

std::size_t frame_budget(const ViewOptions& view, const gui::LodController& lod) {
    return view.point_budget > 0 ? view.point_budget : lod.budget();
}

FrameFacts frame_facts(const HeadlessDriver& driver, const AppState& app, bool busy,
                       const gui::DrawStats& stats) {
    return {.counted = driver.counting(),
            .busy = busy,
            .uploaded = app.link && app.link->uploaded_in_last_poll(),
            .drew_points = stats.points_drawn > 0};
}

void report_frames(const FrameMeter& meter, const AppState& app, const FieldWindow& window,
                   const gui::DrawStats& last, std::size_t budget) {
    meter.report({.last = last,
                  .budget_points = budget,
                  .renderer_name = window.renderer_name(),
                  .points_total = app.renderer->total_points(),
                  .upload_work_ms = app.link ? app.link->upload_work_ms() : std::vector<double>{}});
}

/// The loop of Dear ImGui's example: poll, new frame, build the UI, render, swap. The LOD
/// budget follows the measured frame time unless fixed.
int run_loop(const FieldAppConfig& config, FieldWindow& window, AppState& app) {
    gui::LodController lod({.target_frame_ms = config.view.target_frame_ms});
    HeadlessDriver driver(config.headless, app);
    FrameMeter meter;
    gui::DrawStats stats;
    while (!window.should_close() && !driver.done()) {
        window.wait_events(driver.idle_wait_s(stats.complete));  // poll
        meter.begin();
        window.begin_frame();  // new frame
        poll_session(app);
        gui::UiActions actions;
        driver.step(app, actions);
        meter.polled();
        const bool busy = app.link && app.link->busy(app.view);
        stats = build_and_draw({.font_scale = config.view.font_scale,
                                .budget_points = frame_budget(config.view, lod),
                                .point_size_px = config.view.point_size_px},
                               window, app, actions);  // build the UI, render
        if (auto shot = driver.after_draw(window); !shot) return report_error(shot.error());
        meter.drawn();
        window.swap();
        meter.end(frame_facts(driver, app, busy, stats));
        // Only frames that drew points tell the cost of a budget (cached frames are copies).
        if (meter.frames() > 1 && stats.points_drawn > 0)
            lod.update(meter.last_ms(), app.renderer->total_points());
        if (auto on_time = driver.end_frame(); !on_time) return report_error(on_time.error());
    }
    if (driver.headless()) report_frames(meter, app, window, stats, frame_budget(config.view, lod));
    return 0;
}

}  // namespace

int run_field_app(const FieldAppConfig& config) {
    auto window = FieldWindow::open({.width_px = config.view.width_px,
                                     .height_px = config.view.height_px,
                                     .vsync = config.headless.frames == 0,
                                     .font_scale = config.view.font_scale});
    if (!window) return report_error(window.error());
    AppState app;
    if (auto ready = init_app(config, **window, app); !ready) return report_error(ready.error());
    const int code = run_loop(config, **window, app);
    if (config.dump_state_json) {
        const ViewFigures figures{.points_total = app.renderer->total_points(),
                                  .chunks = app.link ? app.link->shown_scans() : 0,
                                  .camera_preview_rect = camera_preview_rect(),
                                  .mesh_triangles = app.mesh_renderer->triangles()};
        if (auto ok = write_state_json(*config.dump_state_json, app.view, figures); !ok)
            return report_error(ok.error());
    }
    return code;  // shutdown in reverse: the session, the renderer, then the window
}

}  // namespace anascan::field
