#pragma once
/// \file
/// The device panel's scan preview as an OpenGL texture (GL thread only).

#include <cstdint>

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

}  // namespace anascan::field
