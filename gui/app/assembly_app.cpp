#include "assembly_app.hpp"

#include <GL/gl.h>
#include <imgui.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <utility>

#include "anascan/gui/assembly_view.hpp"
#include "anascan/gui/progressive_view.hpp"
#include "anascan/gui/theme.hpp"
#include "anascan/gui/view_picking.hpp"
#include "anascan/processing/core/stopwatch.hpp"
#include "app_state.hpp"
#include "assembly_link.hpp"
#include "field_app.hpp"
#include "field_window.hpp"
#include "screenshot.hpp"
#include "state_dump.hpp"

namespace anascan::field {
namespace {

struct AssemblyApp {
    gui::AssemblyViewState view;
    gui::OrbitCamera camera;
    std::unique_ptr<gui::PointRenderer> renderer;
    std::unique_ptr<gui::ProgressiveView> view_image;
    std::unique_ptr<AssemblyLink> link;
    bool fit_pending = true;
    /// Frames drawn while a worker ran, and the longest of them (the UI never waits).
    std::size_t busy_frames = 0;
    double busy_frame_max_ms = 0.0;
};

/// Four pixels of the view's height around the ray: a click's reach.
constexpr double kPickRadiusPx = 4.0;

/// The 3D view in window pixels (top left origin), as the layout places it.
struct ViewArea {
    float x = 0.0f, y = 0.0f, width = 1.0f, height = 1.0f;
    double aspect() const { return double(width) / double(height); }
    Eigen::Vector2d ndc(float px, float py) const {
        return {2.0 * (px - x) / width - 1.0, 1.0 - 2.0 * (py - y) / height};
    }
    bool contains(float px, float py) const {
        return px >= x && px < x + width && py >= y && py < y + height;
    }
};

ViewArea view_area(const gui::PanelLayout& layout) {
    return {layout.view_x_px(), 0.0f, std::max(1.0f, layout.view_width_px()),
            std::max(1.0f, layout.view_height_px())};
}

/// The face under a point of the view (NDC), as a kPickFace action.
gui::UiAction pick_at(const AssemblyApp& app, const ViewArea& area, const Eigen::Vector2d& ndc) {
    const gui::ViewRay ray = gui::view_ray(app.camera, area.aspect(), ndc);
    const double radius = kPickRadiusPx * app.camera.fov_y_rad() / area.height;
    return {.kind = gui::UiActionKind::kPickFace, .text = app.link->pick_face(ray, radius)};
}

int report_error(const std::string& message) {
    std::fprintf(stderr, "anascan-field: error: %s\n", message.c_str());
    return 1;
}

/// The headless operator: once loaded, tick the pairs, press Align, wait, press Accept,
/// wait; then the frames are counted.
class AssemblyOperator {
public:
    AssemblyOperator(const AssemblyOptions& options, const HeadlessConfig& headless)
        : options_(options), headless_(headless) {}

    bool headless() const { return headless_.frames > 0; }
    bool counting() const { return step_ == Step::kCounting; }
    bool done() const { return headless() && counted_ >= headless_.frames; }

    void step(AssemblyApp& app, const ViewArea& area, gui::UiActions& actions) {
        if (app.view.phase == gui::AssemblyPhase::kFailed) step_ = Step::kCounting;
        if (!headless() || !app.link->settled() || app.view.phase == gui::AssemblyPhase::kLoading ||
            (app.fit_pending && step_ != Step::kCounting))
            return;
        switch (step_) {
            case Step::kChoose:
                click_blocks(app, area, actions);
                for (const std::string& p : options_.choose_pairs) toggle(actions, p);
                if (options_.choose_accepted)
                    for (const std::string& p : app.link->accepted()) toggle(actions, p);
                for (const std::string& p : options_.choose_coplanar)
                    actions.push_back({.kind = gui::UiActionKind::kToggleCoplanar, .text = p});
                step_ = Step::kAlign;
                return;
            case Step::kAlign:
                if (options_.align) actions.push_back({.kind = gui::UiActionKind::kAlignBlocks});
                step_ = Step::kAccept;
                return;
            case Step::kAccept:
                if (options_.accept && app.view.report && app.view.report->ok())
                    actions.push_back({.kind = gui::UiActionKind::kAcceptAssembly});
                step_ = Step::kSettle;
                return;
            case Step::kSettle:
                app.fit_pending = true;
                step_ = Step::kCounting;
                return;
            case Step::kCounting:
                return;
        }
    }

    Expected<void> after_draw(const FieldWindow& window) const {
        if (!headless_.screenshot_png || !counting() || counted_ + 1 != headless_.frames) return {};
        int fb_w = 0, fb_h = 0;
        window.framebuffer_size(fb_w, fb_h);
        return write_screenshot(*headless_.screenshot_png, fb_w, fb_h);
    }

    Expected<void> end_frame() {
        if (counting()) {
            ++counted_;
            return {};
        }
        if (!headless() || started_.seconds() <= headless_.session_timeout_s) return {};
        return fail(ErrorCode::kTimeout,
                    "the assembly did not settle within the timeout "
                    "(loading or alignment still running)");
    }

private:
    enum class Step { kChoose, kAlign, kAccept, kSettle, kCounting };
    /// Clicks where each named block's centre shows (the face in front of it is hit).
    void click_blocks(const AssemblyApp& app, const ViewArea& area, gui::UiActions& actions) {
        for (const std::string& id : options_.click_blocks) {
            const auto centre = app.link->shown_centre(id);
            const auto ndc =
                centre ? gui::project_to_view(app.camera, area.aspect(), *centre) : std::nullopt;
            if (ndc) actions.push_back(pick_at(app, area, *ndc));
        }
    }
    static void toggle(gui::UiActions& actions, const std::string& pair) {
        actions.push_back({.kind = gui::UiActionKind::kTogglePair, .text = pair});
    }
    AssemblyOptions options_;
    HeadlessConfig headless_;
    Step step_ = Step::kChoose;
    int counted_ = 0;
    Stopwatch started_;
};

void apply_actions(const gui::UiActions& actions, AssemblyApp& app) {
    for (const gui::UiAction& action : actions) {
        if (action.kind == gui::UiActionKind::kFitView)
            app.fit_pending = true;
        else if (!gui::apply_assembly_view_action(app.view, action))
            app.link->apply(action, app.view);
    }
}

void draw_scene(AssemblyApp& app, const gui::PanelLayout& layout, int fb_w, int fb_h,
                const FrameDraw& frame) {
    glViewport(0, 0, fb_w, fb_h);
    const gui::PanelBackground bg = gui::panel_background();
    glClearColor(bg.r, bg.g, bg.b, 1.0f);
    glClear(GL_COLOR_BUFFER_BIT | GL_DEPTH_BUFFER_BIT);
    const auto [x, y, w, h] = view_rect(layout, fb_w, fb_h);
    if (app.fit_pending && app.renderer->total_points() > 0) {
        app.camera.fit(app.renderer->bounds(), static_cast<double>(w) / h);
        app.fit_pending = false;
    }
    handle_camera_input(app.camera, static_cast<float>(h));
    app.view_image->render(*app.renderer, app.camera, {x, y, w, h},
                           {.color_mode = gui::ColorMode::kByCoverage,
                            .budget_points = frame.budget_points,
                            .base_point_size_px = frame.point_size_px});
    glViewport(0, 0, fb_w, fb_h);
}

AssemblyLinkConfig link_config(const AssemblyOptions& o) {
    return {.dir = *o.dir,
            .proposals = o.proposals,
            .out = o.out.value_or(*o.dir / "assembly"),
            .fixed = o.fixed};
}

/// A left click (pressed and released within a few pixels, not a drag) on the view, NDC.
std::optional<Eigen::Vector2d> clicked_in_view(const ViewArea& area, std::optional<ImVec2>& press) {
    const ImGuiIO& io = ImGui::GetIO();
    if (io.MouseClicked[0])
        press = !io.WantCaptureMouse && area.contains(io.MousePos.x, io.MousePos.y)
                    ? std::optional<ImVec2>(io.MousePos)
                    : std::nullopt;
    if (!io.MouseReleased[0] || !press) return std::nullopt;
    const ImVec2 at = std::exchange(press, std::nullopt).value();
    if (std::hypot(io.MousePos.x - at.x, io.MousePos.y - at.y) > kPickRadiusPx) return std::nullopt;
    return area.ndc(at.x, at.y);
}

int run_loop(const FieldAppConfig& config, FieldWindow& window, AssemblyApp& app) {
    AssemblyOperator op(config.assembly, config.headless);
    std::optional<ImVec2> press;
    while (!window.should_close() && !op.done()) {
        const bool busy = !app.link->settled();
        const Stopwatch frame_time;
        window.wait_events(op.headless() ? 0.0 : 0.05);
        window.begin_frame();
        if (app.link->poll(app.view, *app.renderer)) app.fit_pending = true;
        gui::UiActions actions;
        const gui::PanelLayout layout = current_layout(config.view.font_scale);
        op.step(app, view_area(layout), actions);
        if (auto click = clicked_in_view(view_area(layout), press))
            actions.push_back(pick_at(app, view_area(layout), *click));
        gui::draw_assembly_panels(app.view, layout, actions);
        apply_actions(actions, app);
        int fb_w = 0, fb_h = 0;
        window.framebuffer_size(fb_w, fb_h);
        draw_scene(
            app, layout, fb_w, fb_h,
            {.budget_points = config.view.point_budget > 0 ? config.view.point_budget : 2'000'000,
             .point_size_px = config.view.point_size_px});
        window.render_ui();
        if (auto shot = op.after_draw(window); !shot) return report_error(shot.error().message);
        window.swap();
        if (busy) {
            ++app.busy_frames;
            app.busy_frame_max_ms = std::max(app.busy_frame_max_ms, 1e3 * frame_time.seconds());
        }
        if (auto on_time = op.end_frame(); !on_time) return report_error(on_time.error().message);
    }
    return 0;
}

}  // namespace

int run_assembly_app(const FieldAppConfig& config) {
    auto window = FieldWindow::open({.width_px = config.view.width_px,
                                     .height_px = config.view.height_px,
                                     .vsync = config.headless.frames == 0,
                                     .font_scale = config.view.font_scale});
    if (!window) return report_error(window.error().message);
    AssemblyApp app;
    auto renderer = gui::PointRenderer::create();
    if (!renderer) return report_error(renderer.error().message);
    app.renderer = std::move(*renderer);
    auto view_image = gui::ProgressiveView::create(kViewBackground);
    if (!view_image) return report_error(view_image.error().message);
    app.view_image = std::move(*view_image);
    gui::apply_theme(
        {.high_contrast = config.view.high_contrast, .font_scale = config.view.font_scale},
        (*window)->font_scaled());
    app.link = std::make_unique<AssemblyLink>(link_config(config.assembly));
    app.link->open(app.view);
    int code = run_loop(config, **window, app);
    if (app.view.phase == gui::AssemblyPhase::kFailed)
        code = report_error(app.view.last_error);
    else if (!app.view.last_error.empty())
        std::fprintf(stderr, "anascan-field: last message: %s\n", app.view.last_error.c_str());
    if (config.dump_state_json)
        if (auto ok = write_assembly_state_json(*config.dump_state_json, app.view,
                                                {.points_total = app.renderer->total_points(),
                                                 .busy_frames = app.busy_frames,
                                                 .busy_frame_max_ms = app.busy_frame_max_ms});
            !ok)
            return report_error(ok.error().message);
    app.link.reset();  // workers finish before the renderer and the window go
    return code;
}

}  // namespace anascan::field
