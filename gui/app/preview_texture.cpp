#include "preview_texture.hpp"

#include <GL/gl.h>
#include <fmt/chrono.h>
#include <fmt/format.h>

namespace anascan::field {
namespace {

/// (Re)fills `texture` (made when 0) with an RGB8 image.
void upload_rgb(unsigned& texture, int width_px, int height_px, const std::uint8_t* rgb) {
    if (texture == 0) glGenTextures(1, &texture);
    glBindTexture(GL_TEXTURE_2D, texture);
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MIN_FILTER, GL_LINEAR);
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MAG_FILTER, GL_LINEAR);
    glPixelStorei(GL_UNPACK_ALIGNMENT, 1);  // rows of 3-byte pixels
    glTexImage2D(GL_TEXTURE_2D, 0, GL_RGB8, width_px, height_px, 0, GL_RGB, GL_UNSIGNED_BYTE, rgb);
    glPixelStorei(GL_UNPACK_ALIGNMENT, 4);
    glBindTexture(GL_TEXTURE_2D, 0);
}

}  // namespace

PreviewTexture::~PreviewTexture() {
    if (texture_ != 0) glDeleteTextures(1, &texture_);
}

void PreviewTexture::show(const gui::ScanPreview& preview, gui::DevicePanelState& device) {
    if (preview.width_px <= 0 || preview.height_px <= 0) return;
    upload_rgb(texture_, preview.width_px, preview.height_px, preview.rgb.data());
    device.preview_texture = texture_;
    device.preview_width_px = preview.width_px;
    device.preview_height_px = preview.height_px;
    device.preview_caption = fmt::format("Scan {} as the scanner saw it ({} points, near bright)",
                                         preview.seq, preview.points);
}

CameraTextures::~CameraTextures() {
    if (!textures_.empty()) glDeleteTextures(static_cast<int>(textures_.size()), textures_.data());
}

void CameraTextures::show(const acquisition::CameraPreview& preview,
                          gui::DevicePanelState& device) {
    textures_.resize(std::max(textures_.size(), preview.images.size()), 0u);
    device.cameras.clear();
    std::vector<std::uint8_t> rgb;
    for (std::size_t i = 0; i < preview.images.size(); ++i) {
        const acquisition::CameraImage& image = preview.images[i];
        rgb.resize(image.grey.size() * 3);
        for (std::size_t p = 0; p < image.grey.size(); ++p)
            rgb[3 * p] = rgb[3 * p + 1] = rgb[3 * p + 2] = image.grey[p];
        upload_rgb(textures_[i], image.width_px, image.height_px, rgb.data());
        device.cameras.push_back({.texture = textures_[i],
                                  .width_px = image.width_px,
                                  .height_px = image.height_px,
                                  .name = fmt::format("cam{}", i + 1)});
    }
    const auto local = fmt::localtime(std::chrono::system_clock::to_time_t(preview.taken_at));
    device.cameras_caption = preview.images.empty()
                                 ? "This device has no cameras to preview"
                                 : fmt::format("cam1 | cam2 at {:%H:%M:%S}", local);
}

}  // namespace anascan::field
