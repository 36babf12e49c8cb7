#pragma once
/// \file
/// What the 3D view draws over the points: a scale bar of a round length, the world axes
/// as the camera sees them, and the legend of the colour mode. The figures are pure
/// functions (tested without GL); draw_view_overlay draws them with ImGui's background
/// draw list (over the points, under the panels). Call between NewFrame and Render.

#include <Eigen/Core>
#include <array>
#include <string>
#include <vector>

#include "anascan/gui/field_view_state.hpp"
#include "anascan/gui/orbit_camera.hpp"
#include "anascan/processing/core/point_cloud.hpp"

namespace anascan::gui {

/// The 3D view in window pixels (top left origin).
struct OverlayRect {
    float x_px = 0.0f, y_px = 0.0f, width_px = 0.0f, height_px = 0.0f;
};

struct ScaleBar {
    double length_m = 0.0;
    float length_px = 0.0f;
    std::string label;  ///< "20 cm", "5 mm", "1 m".
};

/// The longest round length (1, 2 or 5 × 10^k m) that is at most `max_px` long at
/// `metres_per_px`; length 0 when the scale is not positive.
ScaleBar scale_bar(double metres_per_px, float max_px);

/// Metres per pixel at the camera's target (the depth the orbit turns about), for a view
/// `view_height_px` high.
double metres_per_px_at_target(const OrbitCamera& camera, float view_height_px);

/// The world's X, Y and Z axes as the camera sees them: 2-D directions in window pixels'
/// orientation (x right, y down), of length 1 when parallel to the screen, shorter as they
/// point toward or away from the viewer.
std::array<Eigen::Vector2d, 3> axes_on_screen(const OrbitCamera& camera);

struct LegendEntry {
    Rgb8 color;
    std::string label;
    bool ring = false;  ///< Drawn as a ring (a hole marker), not a point.
};

/// The legend of the view's colour mode: by scan, the scans in the view (newest last, at
/// most `max_scans`, with "…" first when there are more); by quality, the classes of
/// quality_color; by coverage, the hole markers in the colour `anascan coverage --ply`
/// gives unobserved samples. The mesh view's legend is its two surface classes, in the
/// colours of the mesh files.
std::vector<LegendEntry> color_legend(const FieldViewState& state, std::size_t max_scans = 8);

/// The legend's title ("Colour by scan", ...).
const char* legend_title(ColorMode mode);

/// Draws the scale bar and the axes (bottom left of the view) and the legend (bottom right).
void draw_view_overlay(const FieldViewState& state, const OrbitCamera& camera,
                       const OverlayRect& view);

}  // namespace anascan::gui
