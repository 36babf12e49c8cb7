#pragma once
/// \file
/// What one run of the field app owns besides the window, and the steps of one frame that
/// use it: take the session's news, build the panels, apply the operator's actions, draw
/// the 3D view. GL thread only.

#include <array>
#include <cstddef>
#include <memory>
#include <optional>

#include "anascan/gui/field_view_state.hpp"
#include "anascan/gui/mesh_renderer.hpp"
#include "anascan/gui/orbit_camera.hpp"
#include "anascan/gui/panels.hpp"
#include "anascan/gui/point_renderer.hpp"
#include "anascan/gui/progressive_view.hpp"
#include "anascan/gui/theme.hpp"
#include "anascan/gui/ui_action.hpp"
#include "anascan/processing/core/expected.hpp"

namespace anascan::field {

struct CloudInputs;
class FieldWindow;
class SessionLink;

/// The view's background (linear RGB, 0..1): dark blue-grey, the points stand out.
inline const Eigen::Vector3f kViewBackground(0.16f, 0.18f, 0.22f);

struct AppState {
    gui::FieldViewState view;
    gui::OrbitCamera camera;
    std::unique_ptr<gui::PointRenderer> renderer;
    std::unique_ptr<gui::MeshRenderer> mesh_renderer;  ///< The fragment model, once made.
    std::unique_ptr<gui::ProgressiveView> view_image;
    gui::ThemeConfig theme;
    bool fit_pending = true;  ///< Fit the camera in the next frame (its aspect is known there).
    std::unique_ptr<SessionLink> link;  ///< With a session.
    AppState();
    ~AppState();
};

/// The renderers and the progressive view (needs the window's GL context).
Expected<void> create_renderer(AppState& app);

/// Loads the PLY files and the synthetic stone into the renderer and the scan list; the
/// renderer keeps the only copy of the points (on the GPU).
Expected<void> load_scans(const CloudInputs& inputs, AppState& app);

/// Events, futures and new points of the session; fits the view to the first points;
/// shows a mesh once it is made.
void poll_session(AppState& app);

/// How the frame draws.
struct FrameDraw {
    float font_scale = 1.5f;
    std::size_t budget_points = 0;  ///< LOD budget of this frame.
    float point_size_px = 2.0f;
};

/// Builds the panels, applies the actions (the panels' and the headless driver's), draws
/// the 3D view and ImGui's draw data; returns the view's draw stats.
gui::DrawStats build_and_draw(const FrameDraw& frame, FieldWindow& window, AppState& app,
                              gui::UiActions& actions);

/// The panels' places for the window's current size.
gui::PanelLayout current_layout(float font_scale);
/// Mouse over the 3D view: left drag orbits, right or middle drag pans, the wheel zooms.
void handle_camera_input(gui::OrbitCamera& camera, float view_height_px);
/// The 3D view's rectangle in frame-buffer pixels (bottom left origin), HiDPI-safe.
std::array<int, 4> view_rect(const gui::PanelLayout& layout, int fb_w, int fb_h);

/// The camera preview's child window in the last frame (for the state dump).
std::optional<std::array<float, 4>> camera_preview_rect();

}  // namespace anascan::field
