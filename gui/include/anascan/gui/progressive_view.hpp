#pragma once
/// \file
/// The point view drawn into an off-screen frame buffer and refined over frames. A camera
/// move, a new scan or a style change starts a fresh image of one budget of points
/// (enlarged to fill the gaps); while nothing changes, each frame adds the next budget of
/// points (the chunks are shuffled, so each slice is uniform) until every point is in; a
/// complete image is only copied to the screen. So a frame costs at most one budget of
/// points, and an idle view of any size costs a copy. Not thread-safe (GL thread only).

#include <Eigen/Core>
#include <memory>

#include "anascan/gui/point_renderer.hpp"

namespace anascan::gui {

/// A rectangle of the default frame buffer, pixels, origin bottom left (as glViewport).
struct ViewRect {
    int x = 0, y = 0, width = 1, height = 1;
    friend bool operator==(const ViewRect&, const ViewRect&) = default;
};

class ProgressiveView {
public:
    /// Needs a current GL 3.3 context. background_rgb: 0..1.
    static Expected<std::unique_ptr<ProgressiveView>> create(const Eigen::Vector3f& background_rgb);
    ~ProgressiveView();
    ProgressiveView(const ProgressiveView&) = delete;
    ProgressiveView& operator=(const ProgressiveView&) = delete;

    /// Draws this frame's slice (if any) and copies the image to `rect` of the default
    /// frame buffer. config.slice_begin_points / enlarge_thinned are set here.
    DrawStats render(PointRenderer& renderer, const OrbitCamera& camera, const ViewRect& rect,
                     DrawConfig config);

private:
    struct Key {
        Eigen::Matrix4d view = Eigen::Matrix4d::Zero();
        ViewRect rect;
        ColorMode color_mode = ColorMode::kByScan;
        std::uint64_t revision = ~std::uint64_t{0};
        bool operator==(const Key& o) const {
            return view == o.view && rect == o.rect && color_mode == o.color_mode &&
                   revision == o.revision;
        }
    };
    ProgressiveView() = default;
    Expected<void> resize(int width, int height);
    void release();

    Eigen::Vector3f background_rgb_ = Eigen::Vector3f::Zero();
    unsigned fbo_ = 0, color_ = 0, depth_ = 0;
    int width_ = 0, height_ = 0;
    Key key_;
    std::size_t in_image_ = 0;
    bool refining_ = false;
    bool complete_ = false;
};

}  // namespace anascan::gui
