#include "app_state.hpp"

#include <GL/gl.h>
#include <imgui.h>
#include <imgui_internal.h>

#include <algorithm>
#include <string>
#include <string_view>

#include "anascan/gui/panels.hpp"
#include "anascan/gui/scan_colors.hpp"
#include "anascan/gui/view_overlay.hpp"
#include "demo_clouds.hpp"
#include "field_app.hpp"
#include "field_window.hpp"
#include "session_link.hpp"

namespace anascan::field {
namespace {

const Eigen::Vector3f& kBackground = kViewBackground;

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

/// The mesh, drawn straight into the view's rectangle each frame (no progressive image: a
/// mesh of a few million triangles draws in one frame).
void draw_mesh(const gui::MeshRenderer& mesh, const gui::OrbitCamera& camera,
               const gui::ViewRect& rect) {
    glEnable(GL_SCISSOR_TEST);
    glScissor(rect.x, rect.y, rect.width, rect.height);
    glClearColor(kBackground.x(), kBackground.y(), kBackground.z(), 1.0f);
    glClear(GL_COLOR_BUFFER_BIT | GL_DEPTH_BUFFER_BIT);
    glDisable(GL_SCISSOR_TEST);
    glViewport(rect.x, rect.y, rect.width, rect.height);
    mesh.draw(camera, static_cast<double>(rect.width) / rect.height);
    glDisable(GL_DEPTH_TEST);
}

/// The 3D view fills the space between the side panels and above the status bar.
gui::DrawStats draw_scene(AppState& app, const gui::PanelLayout& layout, int fb_w, int fb_h,
                          const gui::DrawConfig& draw) {
    glViewport(0, 0, fb_w, fb_h);
    // The panels' background (they draw none: panels.hpp); the view is copied over it.
    const gui::PanelBackground bg = gui::panel_background();
    glClearColor(bg.r, bg.g, bg.b, 1.0f);
    glClear(GL_COLOR_BUFFER_BIT | GL_DEPTH_BUFFER_BIT);
    const auto [x, y, w, h] = view_rect(layout, fb_w, fb_h);
    if (app.fit_pending) {
        app.camera.fit(app.renderer->bounds(), static_cast<double>(w) / h);
        app.fit_pending = false;
    }
    handle_camera_input(app.camera, static_cast<float>(h));
    if (app.view.view_mode == gui::ViewMode::kMesh && app.mesh_renderer->has_mesh()) {
        draw_mesh(*app.mesh_renderer, app.camera, {x, y, w, h});
        glViewport(0, 0, fb_w, fb_h);
        return {.complete = true};
    }
    const gui::DrawStats stats =
        app.view_image->render(*app.renderer, app.camera, {x, y, w, h}, draw);
    glViewport(0, 0, fb_w, fb_h);
    return stats;
}

}  // namespace

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

void handle_camera_input(gui::OrbitCamera& camera, float view_height_px) {
    const ImGuiIO& io = ImGui::GetIO();
    if (io.WantCaptureMouse) return;
    if (io.MouseDown[0]) camera.orbit(io.MouseDelta.x, io.MouseDelta.y);
    if (io.MouseDown[1] || io.MouseDown[2]) {
        camera.pan(io.MouseDelta.x, io.MouseDelta.y, view_height_px);
    }
    if (io.MouseWheel != 0.0f) camera.zoom(io.MouseWheel);
}

std::array<int, 4> view_rect(const gui::PanelLayout& layout, int fb_w, int fb_h) {
    const float sx = static_cast<float>(fb_w) / std::max(layout.width_px, 1.0f);
    const float sy = static_cast<float>(fb_h) / std::max(layout.height_px, 1.0f);
    return {static_cast<int>(layout.view_x_px() * sx),
            static_cast<int>(layout.status_height_px * sy),
            std::max(1, static_cast<int>(layout.view_width_px() * sx)),
            std::max(1, static_cast<int>(layout.view_height_px() * sy))};
}

AppState::AppState() = default;
AppState::~AppState() = default;

Expected<void> create_renderer(AppState& app) {
    auto renderer = gui::PointRenderer::create();
    if (!renderer) return fail(renderer.error());
    app.renderer = std::move(*renderer);
    auto mesh_renderer = gui::MeshRenderer::create();
    if (!mesh_renderer) return fail(mesh_renderer.error());
    app.mesh_renderer = std::move(*mesh_renderer);
    auto view_image = gui::ProgressiveView::create(kBackground);
    if (!view_image) return fail(view_image.error());
    app.view_image = std::move(*view_image);
    return {};
}

Expected<void> load_scans(const CloudInputs& inputs, AppState& app) {
    std::int64_t seq = 0;
    for (const auto& path : inputs.clouds) {
        auto scan = load_ply_scan(path, ++seq);
        if (!scan) return fail(scan.error());
        app.view.scans.push_back(scan->row);
        app.renderer->add_chunk(seq, std::move(scan->cloud), Eigen::Isometry3d::Identity());
    }
    if (inputs.synthetic_points == 0) return {};
    for (LoadedScan& scan :
         synthetic_stone({.points = inputs.synthetic_points, .scans = inputs.synthetic_scans})) {
        scan.row.seq = ++seq;
        app.view.scans.push_back(scan.row);
        app.renderer->add_chunk(seq, std::move(scan.cloud), Eigen::Isometry3d::Identity());
    }
    return {};
}

void poll_session(AppState& app) {
    if (!app.link) return;
    const bool had_points = app.renderer->total_points() > 0;
    app.link->poll(app.view, *app.renderer);
    if (!had_points && app.renderer->total_points() > 0) app.fit_pending = true;
    if (std::optional<Mesh> mesh = app.link->take_mesh()) {
        app.mesh_renderer->set_mesh(*mesh);
        app.view.view_mode = gui::ViewMode::kMesh;  // the operator asked for it: show it
    }
}

gui::DrawStats build_and_draw(const FrameDraw& frame, FieldWindow& window, AppState& app,
                              gui::UiActions& actions) {
    const gui::PanelLayout layout = current_layout(frame.font_scale);
    gui::draw_field_panels(app.view, layout, actions);
    apply_actions(actions, app, window.font_scaled());
    update_styles(app);
    gui::draw_view_overlay(app.view, app.camera,
                           {.x_px = layout.view_x_px(),
                            .y_px = 0.0f,
                            .width_px = layout.view_width_px(),
                            .height_px = layout.view_height_px()});
    int fb_w = 0, fb_h = 0;
    window.framebuffer_size(fb_w, fb_h);
    const gui::DrawStats stats = draw_scene(app, layout, fb_w, fb_h,
                                            {.color_mode = app.view.color_mode,
                                             .budget_points = frame.budget_points,
                                             .base_point_size_px = frame.point_size_px});
    window.render_ui();
    return stats;
}

std::optional<std::array<float, 4>> camera_preview_rect() {
    const std::string suffix = std::string("/") + gui::kCameraPreviewChild + "_";
    for (const ImGuiWindow* w : ImGui::GetCurrentContext()->Windows) {
        if (!w->WasActive || std::string_view(w->Name).find(suffix) == std::string_view::npos)
            continue;
        return std::array<float, 4>{w->Pos.x, w->Pos.y, w->Size.x, w->Size.y};
    }
    return std::nullopt;
}

}  // namespace anascan::field
