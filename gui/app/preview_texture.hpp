#pragma once
/// \file
/// The device panel's images as OpenGL textures (GL thread only): the last scan's preview
/// and the live camera preview.

#include <cstdint>
#include <vector>

#include "anascan/acquisition/capture/device_control.hpp"
#include "anascan/gui/field_view_state.hpp"
#include "anascan/gui/scan_preview.hpp"

namespace anascan::field {

class PreviewTexture {
public:
    PreviewTexture() = default;
    ~PreviewTexture();
    PreviewTexture(const PreviewTexture&) = delete;
    PreviewTexture& operator=(const PreviewTexture&) = delete;

    /// Uploads the preview (replacing the last) and points the device panel at it.
    void show(const gui::ScanPreview& preview, gui::DevicePanelState& device);

private:
    unsigned texture_ = 0;
};

/// One texture per camera of the live preview, replaced at each new image.
class CameraTextures {
public:
    CameraTextures() = default;
    ~CameraTextures();
    CameraTextures(const CameraTextures&) = delete;
    CameraTextures& operator=(const CameraTextures&) = delete;

    /// Uploads the cameras' images and points the device panel at them, with the caption.
    void show(const acquisition::CameraPreview& preview, gui::DevicePanelState& device);

private:
    std::vector<unsigned> textures_;
};

}  // namespace anascan::field
