#include "field_app.hpp"

#include <GL/gl.h>
#include <imgui.h>
#include <imgui_internal.h>

#include <chrono>
#include <cstdio>

#include "anascan/gui/level_of_detail.hpp"
#include "anascan/gui/panels.hpp"
#include "anascan/gui/point_renderer.hpp"
#include "anascan/gui/progressive_view.hpp"
#include "anascan/gui/scan_colors.hpp"
#include "anascan/gui/theme.hpp"
#include "demo_clouds.hpp"
#include "field_window.hpp"
#include "frame_times.hpp"
#include "headless_device.hpp"
#include "screenshot.hpp"
#include "session_link.hpp"
#include "state_dump.hpp"

namespace anascan::field {
namespace {

/// The view's background (linear RGB, 0..1): dark blue-grey, the points stand out.
const Eigen::Vector3f kBackground(0.16f, 0.18f, 0.22f);

/// Everything one run of the app owns besides the window.
struct AppState {
    gui::FieldViewState view;
    gui::OrbitCamera camera;
    std::unique_ptr<gui::PointRenderer> renderer;
    std::unique_ptr<gui::ProgressiveView> view_image;
    gui::ThemeConfig theme;
    bool fit_pending = true;  ///< Fit the camera in the next frame (its aspect is known there).
    std::unique_ptr<SessionLink> link;  ///< With --session.
    bool reregister_sent = false;       ///< Headless --reregister-scan done.
    bool connect_sent = false;          ///< Headless --connect done.
    bool settings_sent = false;         ///< Headless --apply-setting done.
};

/// A headless run with a session: capture (--capture-views), wait until the session has
/// settled (registration done, points loaded), re-register a scan (--reregister-scan) and
/// settle again, then count the --frames.
enum class Phase { kCapturing, kSettling, kReregistering, kCounting };

/// The camera preview's child window in the last frame (for the state dump).
std::optional<std::array<float, 4>> camera_preview_rect() {
    const std::string suffix = std::string("/") + gui::kCameraPreviewChild + "_";
    for (const ImGuiWindow* w : ImGui::GetCurrentContext()->Windows) {
        if (!w->WasActive || std::string_view(w->Name).find(suffix) == std::string_view::npos)
            continue;
        return std::array<float, 4>{w->Pos.x, w->Pos.y, w->Size.x, w->Size.y};
    }
    return std::nullopt;
}

/// Loads the PLY files and the synthetic stone into the renderer and the scan list; the
/// renderer keeps the only copy of the points (on the GPU).
Expected<void> load_scans(const FieldAppConfig& config, AppState& app) {
    std::int64_t seq = 0;
    for (const auto& path : config.clouds) {
        auto scan = load_ply_scan(path, ++seq);
        if (!scan) return fail(scan.error());
        app.view.scans.push_back(scan->row);
        app.renderer->add_chunk(seq, std::move(scan->cloud), Eigen::Isometry3d::Identity());
    }
    if (config.synthetic_points > 0) {
        for (LoadedScan& scan : synthetic_stone(
                 {.points = config.synthetic_points, .scans = config.synthetic_scans})) {
            scan.row.seq = ++seq;
            app.view.scans.push_back(scan.row);
            app.renderer->add_chunk(seq, std::move(scan.cloud), Eigen::Isometry3d::Identity());
        }
    }
    return {};
}

/// Chunk styles follow the view state: palette, quality, exclusion, highlight.
void update_styles(AppState& app) {
    const std::int64_t highlight =
        app.view.selected_seq >= 0 ? app.view.selected_seq : gui::newest_scan(app.view);
    for (const gui::ScanRow& row : app.view.scans) {
        app.renderer->set_style(row.seq, {.scan_color = gui::scan_palette_color(row.seq),
                                          .quality_color = gui::quality_color(row),
                                          .visible = row.state != gui::ScanRowState::kExcluded,
                                          .highlighted = row.seq == highlight});
    }
}

gui::PanelLayout current_layout(float font_scale) {
    const ImGuiIO& io = ImGui::GetIO();
    const ImGuiStyle& style = ImGui::GetStyle();
    return {.width_px = io.DisplaySize.x,
            .height_px = io.DisplaySize.y,
            .scan_list_width_px = 300.0f * font_scale,
            .device_width_px = 240.0f * font_scale,
            .status_height_px = ImGui::GetFrameHeight() + 2.0f * style.WindowPadding.y,
            .banner_height_px = 90.0f * font_scale};
}

/// Mouse over the 3D view: left drag orbits, right or middle drag pans, the wheel zooms.
void handle_camera_input(gui::OrbitCamera& camera, float view_height_px) {
    const ImGuiIO& io = ImGui::GetIO();
    if (io.WantCaptureMouse) return;
    if (io.MouseDown[0]) camera.orbit(io.MouseDelta.x, io.MouseDelta.y);
    if (io.MouseDown[1] || io.MouseDown[2]) {
        camera.pan(io.MouseDelta.x, io.MouseDelta.y, view_height_px);
    }
    if (io.MouseWheel != 0.0f) camera.zoom(io.MouseWheel);
}

/// View actions change the state; session actions wait for the capture session.
void apply_actions(const gui::UiActions& actions, AppState& app, bool font_scaled) {
    for (const gui::UiAction& action : actions) {
        if (action.kind == gui::UiActionKind::kFitView) {
            app.fit_pending = true;
        } else if (action.kind == gui::UiActionKind::kToggleContrast) {
            gui::apply_view_action(app.view, action);
            app.theme.high_contrast = app.view.high_contrast;
            gui::apply_theme(app.theme, font_scaled);
        } else if (gui::apply_view_action(app.view, action)) {
        } else if (app.link && app.link->apply(action, app.view)) {
        } else {
            app.view.status.last_error =
                "no capture session: start anascan-field with --session DIR to capture";
        }
    }
}

/// The 3D view fills the space between the side panels and above the status bar.
gui::DrawStats draw_scene(AppState& app, const gui::PanelLayout& layout, int fb_w, int fb_h,
                          const gui::DrawConfig& draw) {
    glViewport(0, 0, fb_w, fb_h);
    // The panels' background (they draw none: panels.hpp); the view is copied over it.
    const gui::PanelBackground bg = gui::panel_background();
    glClearColor(bg.r, bg.g, bg.b, 1.0f);
    glClear(GL_COLOR_BUFFER_BIT | GL_DEPTH_BUFFER_BIT);
    // Window pixels (top left) to frame-buffer pixels (bottom left), HiDPI-safe.
    const float sx = static_cast<float>(fb_w) / std::max(layout.width_px, 1.0f);
    const float sy = static_cast<float>(fb_h) / std::max(layout.height_px, 1.0f);
    const int x = static_cast<int>(layout.view_x_px() * sx);
    const int y = static_cast<int>(layout.status_height_px * sy);
    const int w = std::max(1, static_cast<int>(layout.view_width_px() * sx));
    const int h = std::max(1, static_cast<int>(layout.view_height_px() * sy));
    if (app.fit_pending) {
        app.camera.fit(app.renderer->bounds(), static_cast<double>(w) / h);
        app.fit_pending = false;
    }
    handle_camera_input(app.camera, static_cast<float>(h));
    const gui::DrawStats stats =
        app.view_image->render(*app.renderer, app.camera, {x, y, w, h}, draw);
    glViewport(0, 0, fb_w, fb_h);
    return stats;
}

/// Frame times on stderr: all frames, and those that drew points apart from the copies of
/// a complete image.
void report(const std::vector<double>& frame_ms, const std::vector<bool>& drew,
            const gui::DrawStats& last, std::size_t budget, const std::string& renderer_name) {
    // The first frame compiles shaders and fills caches: it is not a steady-state frame.
    std::vector<double> steady, drawing, copies;
    for (std::size_t i = 1; i < frame_ms.size(); ++i) {
        steady.push_back(frame_ms[i]);
        (drew[i] ? drawing : copies).push_back(frame_ms[i]);
    }
    const FrameTimeSummary s = summarize_frame_times(steady);
    const FrameTimeSummary d = summarize_frame_times(drawing);
    const FrameTimeSummary c = summarize_frame_times(copies);
    std::fprintf(stderr,
                 "anascan-field: %zu frames (first excluded): frame time median %.1f ms, "
                 "p95 %.1f ms, max %.1f ms\n"
                 "  %zu frames drew points: median %.1f ms, p95 %.1f ms; %zu copied the complete "
                 "image: median %.1f ms, p95 %.1f ms\n"
                 "  image holds %zu of %zu points (budget %zu points per frame); GL renderer %s\n",
                 steady.size(), s.median_ms, s.p95_ms, s.max_ms, drawing.size(), d.median_ms,
                 d.p95_ms, copies.size(), c.median_ms, c.p95_ms, last.points_in_image,
                 last.points_visible, budget, renderer_name.c_str());
}

Phase initial_phase(const FieldAppConfig& config, const AppState& app) {
    if (!app.link || config.frames == 0) return Phase::kCounting;
    return config.capture_views > 0 ? Phase::kCapturing : Phase::kSettling;
}

/// Headless device panel steps once settled: "Connect", then the settings typed and
/// applied; true when one was taken (the session then settles again).
bool device_steps(const FieldAppConfig& config, AppState& app, gui::UiActions& actions) {
    if (config.connect_device && !std::exchange(app.connect_sent, true)) {
        actions.push_back({.kind = gui::UiActionKind::kOpenDevice});
        return true;
    }
    if (config.apply_settings.empty() || std::exchange(app.settings_sent, true)) return false;
    auto steps = setting_actions(app.view.device.settings, config.apply_settings);
    if (!steps) {
        app.view.device.settings.message = "Not applied: " + steps.error().message;
        app.view.device.settings.message_is_error = true;
        std::fprintf(stderr, "anascan-field: error: %s\n", steps.error().message.c_str());
        return false;
    }
    actions.insert(actions.end(), steps->begin(), steps->end());
    return true;
}

/// The capture action, as the button gives it, whenever no capture runs, until
/// `capture_views` captures have finished; then wait for registration and the view.
Phase drive_session(const FieldAppConfig& config, AppState& app, Phase phase,
                    gui::UiActions& actions) {
    if (phase == Phase::kCapturing) {
        if (app.link->captures_finished() >= config.capture_views) {
            app.link->request_idle();
            return Phase::kSettling;
        }
        if (!app.link->capturing()) actions.push_back({.kind = gui::UiActionKind::kCapture});
        return phase;
    }
    if (phase == Phase::kReregistering) {  // the action was applied in the last frame
        app.link->request_idle();
        return Phase::kSettling;
    }
    if (phase == Phase::kSettling && app.link->settled()) {
        if (device_steps(config, app, actions)) return Phase::kSettling;  // then settle again
        if (config.reregister_seq > 0 && !app.reregister_sent) {
            actions.push_back(
                {.kind = gui::UiActionKind::kReRegister, .seq = config.reregister_seq});
            app.reregister_sent = true;
            return Phase::kReregistering;
        }
        app.fit_pending = true;  // the whole model in the screenshot
        return Phase::kCounting;
    }
    return phase;
}

/// Events, futures and new points of the session; fit the view to the first points.
void poll_session(AppState& app) {
    if (!app.link) return;
    const bool had_points = app.renderer->total_points() > 0;
    app.link->poll(app.view, *app.renderer);
    if (!had_points && app.renderer->total_points() > 0) app.fit_pending = true;
}

/// Frame times while a capture or registrations were pending (the figure).
void report_busy(const std::vector<double>& busy_ms, std::size_t points) {
    if (busy_ms.empty()) return;
    const FrameTimeSummary b = summarize_frame_times(busy_ms);
    std::fprintf(stderr,
                 "anascan-field: %zu frames while capturing or registering: frame time median "
                 "%.1f ms, p95 %.1f ms, max %.1f ms (%zu points in the view at the end)\n",
                 busy_ms.size(), b.median_ms, b.p95_ms, b.max_ms, points);
}

/// Frames that copied a new scan's points to the GPU (all of a scan, or a step of it).
/// and the time the upload itself took in them (taking the scan, copying its points).
void report_uploads(const std::vector<double>& upload_ms, const std::vector<double>& work_ms) {
    if (upload_ms.empty()) return;
    const FrameTimeSummary u = summarize_frame_times(upload_ms);
    const FrameTimeSummary w = summarize_frame_times(work_ms);
    std::fprintf(stderr,
                 "anascan-field: %zu frames uploaded points: frame time median %.1f ms, p95 "
                 "%.1f ms, max %.1f ms; the upload's own work median %.2f ms, max %.2f ms\n",
                 upload_ms.size(), u.median_ms, u.p95_ms, u.max_ms, w.median_ms, w.max_ms);
}

/// Frames over the threshold: the mean of each part, and of the UI thread's CPU time.
void report_slow(const SlowFrames& slow) {
    if (slow.count == 0) return;
    const double n = slow.count;
    std::fprintf(stderr,
                 "anascan-field: %d frames over %.0f ms: mean %.0f ms = session poll %.1f + "
                 "panels, scene and ImGui draw %.1f + swap %.1f ms; the UI thread ran %.1f "
                 "ms of it on a CPU\n",
                 slow.count, slow.threshold_ms, slow.wall_ms / n, slow.poll_ms / n,
                 slow.draw_ms / n, slow.swap_ms / n, slow.cpu_ms / n);
}

struct FrameLog {
    SlowFrames slow;
    std::vector<double> frame_ms, busy_ms;
    std::vector<double> upload_ms;  ///< Frames that copied a new scan's points to the GPU.
    std::vector<bool> drew;
};

/// Draws one frame; returns its stats. `counting`: the frame counts toward --frames.
gui::DrawStats draw_frame(const FieldAppConfig& config, FieldWindow& window, AppState& app,
                          gui::UiActions& actions, std::size_t budget) {
    const gui::PanelLayout layout = current_layout(config.font_scale);
    app.camera.orbit(config.orbit_px_per_frame, 0.0);  // simulated operator (measuring)
    gui::draw_field_panels(app.view, layout, actions);
    apply_actions(actions, app, window.font_scaled());
    update_styles(app);
    int fb_w = 0, fb_h = 0;
    window.framebuffer_size(fb_w, fb_h);
    const gui::DrawStats stats = draw_scene(app, layout, fb_w, fb_h,
                                            {.color_mode = app.view.color_mode,
                                             .budget_points = budget,
                                             .base_point_size_px = config.point_size_px});
    window.render_ui();
    return stats;
}

/// init → loop (poll, new frame, panels, scene, UI, screenshot, swap) as Dear ImGui's
/// example; the LOD budget follows the measured frame time unless fixed.
int run_loop(const FieldAppConfig& config, FieldWindow& window, AppState& app) {
    gui::LodController lod({.target_frame_ms = config.target_frame_ms});
    FrameLog log;
    gui::DrawStats stats;
    Phase phase = initial_phase(config, app);
    const auto started = std::chrono::steady_clock::now();
    int counted = 0;
    for (int frame = 0; config.frames == 0 || counted < config.frames; ++frame) {
        if (window.should_close()) break;
        // Nothing left to refine: sleep until input (or 50 ms, for live updates) instead of
        // spinning, so that capture and registration get the CPU. Headless runs do the same
        // until they count their --frames, which are drawn back to back. A frame's time is
        // counted from the end of that wait: the time to react and draw.
        const bool idle = (config.frames == 0 || phase != Phase::kCounting) && stats.complete &&
                          !ImGui::IsAnyMouseDown();
        window.wait_events(idle ? 0.05 : 0.0);
        const auto start = std::chrono::steady_clock::now();
        const double cpu_start = thread_cpu_ms();
        window.begin_frame();
        poll_session(app);
        gui::UiActions actions;
        if (app.link) phase = drive_session(config, app, phase, actions);
        const auto polled = std::chrono::steady_clock::now();
        const bool counting = phase == Phase::kCounting;
        const bool busy = app.link && app.link->busy(app.view);
        const std::size_t budget = config.point_budget > 0 ? config.point_budget : lod.budget();
        stats = draw_frame(config, window, app, actions, budget);
        if (config.screenshot_png && counting && counted + 1 == config.frames) {
            int fb_w = 0, fb_h = 0;
            window.framebuffer_size(fb_w, fb_h);
            if (auto written = write_screenshot(*config.screenshot_png, fb_w, fb_h); !written) {
                std::fprintf(stderr, "anascan-field: error: %s\n", written.error().message.c_str());
                return 1;
            }
        }
        const auto drawn = std::chrono::steady_clock::now();
        window.swap();
        const auto end = std::chrono::steady_clock::now();
        const std::chrono::duration<double, std::milli> took = end - start;
        if (frame > 0) {
            using Ms = std::chrono::duration<double, std::milli>;
            log.slow.add(took.count(), Ms(polled - start).count(), Ms(drawn - polled).count(),
                         Ms(end - drawn).count(), thread_cpu_ms() - cpu_start);
        }
        if (counting) {
            log.frame_ms.push_back(took.count());
            log.drew.push_back(stats.points_drawn > 0);
            ++counted;
        }
        if (busy && frame > 0) log.busy_ms.push_back(took.count());
        if (app.link && app.link->uploaded_in_last_poll()) log.upload_ms.push_back(took.count());
        // Only frames that drew points tell the cost of a budget (cached frames are copies).
        if (frame > 0 && stats.points_drawn > 0) {
            lod.update(took.count(), app.renderer->total_points());
        }
        const std::chrono::duration<double> waited = std::chrono::steady_clock::now() - started;
        if (!counting && waited.count() > config.session_timeout_s) {
            std::fprintf(stderr,
                         "anascan-field: error: the session did not settle within %.0f s "
                         "(captures or registration still running)\n",
                         config.session_timeout_s);
            return 1;
        }
    }
    if (config.frames > 0) {
        report(log.frame_ms, log.drew, stats,
               config.point_budget > 0 ? config.point_budget : lod.budget(),
               window.renderer_name());
        report_busy(log.busy_ms, app.renderer->total_points());
        if (app.link) report_uploads(log.upload_ms, app.link->upload_work_ms());
        report_slow(log.slow);
    }
    return 0;
}

SessionLinkConfig session_link_config(const FieldAppConfig& config) {
    SessionLinkConfig link{
        .dir = *config.session,
        .device_uri = config.device,
        .tour = {.views = config.tour_views,
                 .flip_after = config.flip_after < 0 ? config.tour_views / 2 : config.flip_after},
        .sim_unplug_after = config.sim_unplug_after,
        .worker_nice = config.worker_nice,
        .upload_points_per_frame = config.upload_points_per_frame};
    link.settings.angular_step_deg = config.angular_step_deg;
    return link;
}

}  // namespace

int run_field_app(const FieldAppConfig& config) {
    auto window = FieldWindow::open({.width_px = config.width_px,
                                     .height_px = config.height_px,
                                     .vsync = config.frames == 0,
                                     .font_scale = config.font_scale});
    if (!window) {
        std::fprintf(stderr, "anascan-field: error: %s\n", window.error().message.c_str());
        return 1;
    }
    AppState app;
    auto renderer = gui::PointRenderer::create();
    if (!renderer) {
        std::fprintf(stderr, "anascan-field: error: %s\n", renderer.error().message.c_str());
        return 1;
    }
    app.renderer = std::move(*renderer);
    auto view_image = gui::ProgressiveView::create(kBackground);
    if (!view_image) {
        std::fprintf(stderr, "anascan-field: error: %s\n", view_image.error().message.c_str());
        return 1;
    }
    app.view_image = std::move(*view_image);
    if (auto loaded = load_scans(config, app); !loaded) {
        std::fprintf(stderr, "anascan-field: error: %s\n", loaded.error().message.c_str());
        return 1;
    }
    app.view.color_mode = config.color_mode;
    app.view.high_contrast = config.high_contrast;
    app.theme = {.high_contrast = config.high_contrast, .font_scale = config.font_scale};
    gui::apply_theme(app.theme, (*window)->font_scaled());
    if (config.session) {
        app.link = std::make_unique<SessionLink>(session_link_config(config));
        app.link->open(app.view);
    }
    const int code = run_loop(config, **window, app);
    if (config.dump_state_json) {
        const ViewFigures figures{.points_total = app.renderer->total_points(),
                                  .chunks = app.link ? app.link->shown_scans() : 0,
                                  .camera_preview_rect = camera_preview_rect()};
        if (auto ok = write_state_json(*config.dump_state_json, app.view, figures); !ok) {
            std::fprintf(stderr, "anascan-field: error: %s\n", ok.error().message.c_str());
            return 1;
        }
    }
    return code;
}

}  // namespace anascan::field
