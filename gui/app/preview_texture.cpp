#include "preview_texture.hpp"

#include <GL/gl.h>
#include <fmt/format.h>

namespace anascan::field {

PreviewTexture::~PreviewTexture() {
    if (texture_ != 0) glDeleteTextures(1, &texture_);
}

void PreviewTexture::show(const gui::ScanPreview& preview, gui::DevicePanelState& device) {
    if (preview.width_px <= 0 || preview.height_px <= 0) return;
    if (texture_ == 0) glGenTextures(1, &texture_);
    glBindTexture(GL_TEXTURE_2D, texture_);
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MIN_FILTER, GL_LINEAR);
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MAG_FILTER, GL_LINEAR);
    glPixelStorei(GL_UNPACK_ALIGNMENT, 1);  // rows of 3-byte pixels
    glTexImage2D(GL_TEXTURE_2D, 0, GL_RGB8, preview.width_px, preview.height_px, 0, GL_RGB,
                 GL_UNSIGNED_BYTE, preview.rgb.data());
    glPixelStorei(GL_UNPACK_ALIGNMENT, 4);
    glBindTexture(GL_TEXTURE_2D, 0);
    device.preview_texture = texture_;
    device.preview_width_px = preview.width_px;
    device.preview_height_px = preview.height_px;
    device.preview_caption = fmt::format("Scan {} as the scanner saw it ({} points, near bright)",
                                         preview.seq, preview.points);
}

}  // namespace anascan::field
