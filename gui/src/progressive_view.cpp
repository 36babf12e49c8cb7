#include "anascan/gui/progressive_view.hpp"

#include "gl_api.hpp"

namespace anascan::gui {

Expected<std::unique_ptr<ProgressiveView>> ProgressiveView::create(
    const Eigen::Vector3f& background_rgb) {
    std::unique_ptr<ProgressiveView> view(new ProgressiveView());
    view->background_rgb_ = background_rgb;
    return view;
}

ProgressiveView::~ProgressiveView() { release(); }

void ProgressiveView::release() {
    if (fbo_ != 0) glDeleteFramebuffers(1, &fbo_);
    if (color_ != 0) glDeleteRenderbuffers(1, &color_);
    if (depth_ != 0) glDeleteRenderbuffers(1, &depth_);
    fbo_ = color_ = depth_ = 0;
    width_ = height_ = 0;
}

Expected<void> ProgressiveView::resize(int width, int height) {
    release();
    glGenFramebuffers(1, &fbo_);
    glBindFramebuffer(GL_FRAMEBUFFER, fbo_);
    glGenRenderbuffers(1, &color_);
    glBindRenderbuffer(GL_RENDERBUFFER, color_);
    glRenderbufferStorage(GL_RENDERBUFFER, GL_RGBA8, width, height);
    glFramebufferRenderbuffer(GL_FRAMEBUFFER, GL_COLOR_ATTACHMENT0, GL_RENDERBUFFER, color_);
    glGenRenderbuffers(1, &depth_);
    glBindRenderbuffer(GL_RENDERBUFFER, depth_);
    glRenderbufferStorage(GL_RENDERBUFFER, GL_DEPTH_COMPONENT24, width, height);
    glFramebufferRenderbuffer(GL_FRAMEBUFFER, GL_DEPTH_ATTACHMENT, GL_RENDERBUFFER, depth_);
    const GLenum status = glCheckFramebufferStatus(GL_FRAMEBUFFER);
    glBindFramebuffer(GL_FRAMEBUFFER, 0);
    if (status != GL_FRAMEBUFFER_COMPLETE) {
        release();
        return fail(ErrorCode::kUnsupported, "point view: off-screen frame buffer incomplete");
    }
    width_ = width;
    height_ = height;
    return {};
}

DrawStats ProgressiveView::render(PointRenderer& renderer, const OrbitCamera& camera,
                                  const ViewRect& rect, DrawConfig config) {
    DrawStats stats{.points_visible = renderer.total_points(), .complete = true};
    if ((rect.width != width_ || rect.height != height_) && !resize(rect.width, rect.height)) {
        return stats;  // nothing drawn; the caller's cleared background stays
    }
    const double aspect = static_cast<double>(rect.width) / rect.height;
    const Key key{.view = camera.projection(aspect) * camera.view().matrix(),
                  .rect = rect,
                  .color_mode = config.color_mode,
                  .revision = renderer.revision()};
    const bool fresh = !(key == key_);
    if (fresh || !complete_) {
        glBindFramebuffer(GL_FRAMEBUFFER, fbo_);
        glViewport(0, 0, width_, height_);
        if (fresh || !refining_) {
            // A fresh (thinned) image, or the start of the refinement at the base size.
            glClearColor(background_rgb_.x(), background_rgb_.y(), background_rgb_.z(), 1.0f);
            glClear(GL_COLOR_BUFFER_BIT | GL_DEPTH_BUFFER_BIT);
            in_image_ = 0;
            refining_ = !fresh;
        }
        config.slice_begin_points = in_image_;
        config.enlarge_thinned = fresh;
        stats = renderer.draw(camera, aspect, config);
        in_image_ = stats.points_in_image;
        complete_ = stats.complete;
        key_ = key;
    }
    stats.points_in_image = in_image_;
    stats.complete = complete_;
    glBindFramebuffer(GL_READ_FRAMEBUFFER, fbo_);
    glBindFramebuffer(GL_DRAW_FRAMEBUFFER, 0);
    glBlitFramebuffer(0, 0, width_, height_, rect.x, rect.y, rect.x + rect.width,
                      rect.y + rect.height, GL_COLOR_BUFFER_BIT, GL_NEAREST);
    glBindFramebuffer(GL_FRAMEBUFFER, 0);
    return stats;
}

}  // namespace anascan::gui
